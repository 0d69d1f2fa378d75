#include <scenes/car_skin.hpp>

#include <deform/surface_projection.hpp>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <variant>

namespace scenes {

std::shared_ptr<const deform::Skin> CarSkin::buildSkin(const deform::Mesh& body,
                                                       const std::vector<Eigen::Vector3d>& control_rest_m,
                                                       const vehicle::DeformationSettings& settings) {
  return std::make_shared<const deform::Skin>(deform::Skin::build(
      body.positions_m, control_rest_m, {settings.alpha, settings.k_nearest, 0, settings.skin_method}));
}

std::shared_ptr<const CarSkin::Build> CarSkin::share(const deform::Mesh& body,
                                                     std::shared_ptr<const deform::Skin> skin) {
  auto build = std::make_shared<Build>();
  build->skin = std::move(skin);
  build->rest_m = body.positions_m;
  build->triangles = body.triangles;
  build->around = std::make_shared<const deform::VertexTriangles>(body.triangles, body.positions_m.size());
  // The body's own normals until something moves; without them, computed here once for every car.
  build->normals_from_triangles = body.normals.size() != body.positions_m.size();
  if (build->normals_from_triangles)
    deform::VertexNormals(build->around).computeAll(body.positions_m, body.triangles, build->rest_normals);
  else
    build->rest_normals = body.normals;
  build->grid = deform::VertexGrid(body.positions_m);
  build->interior_m = 0.5 * (build->grid.bounds().min_m + build->grid.bounds().max_m);
  // |v - v0| <= gain x max_i |d_i| (deform::Skin::displacementGain): 1 for idw, more for mls's negative
  // weights and the spline's.
  build->nonnegative_weights = build->skin->nonnegativeWeights();
  build->displacement_gain = build->skin->displacementGain();
  return build;
}

std::size_t CarSkin::Build::bytes() const {
  return skin->memoryBytes() + (rest_m.capacity() + rest_normals.capacity()) * sizeof(Eigen::Vector3f) +
         triangles.capacity() * sizeof(deform::Triangle) + around->bytes() + grid.bytes();
}

CarSkin::CarSkin(const deform::Mesh& body, const std::vector<Eigen::Vector3d>& control_rest_m,
                 const vehicle::DeformationSettings& settings)
    : CarSkin(share(body, buildSkin(body, control_rest_m, settings))) {}

CarSkin::CarSkin(std::shared_ptr<const Build> build)
    : build_(std::move(build)),
      positions_m_(build_->rest_m),
      normals_(build_->rest_normals),
      last_displacements_m_(build_->skin->controlPointCount(), Eigen::Vector3d::Zero()),
      moved_(build_->skin->controlPointCount(), 0),
      normal_updates_(build_->around),
      normals_computed_(build_->normals_from_triangles),
      is_projected_(build_->rest_m.size(), 0) {}

deform::Mesh CarSkin::deformedMesh() const {
  deform::Mesh mesh;
  mesh.positions_m = positions_m_;
  mesh.triangles = build_->triangles;
  mesh.normals = normals_;
  return mesh;
}

std::size_t CarSkin::ownBytes() const {
  return (positions_m_.capacity() + normals_.capacity() + projected_from_m_.capacity()) *
             sizeof(Eigen::Vector3f) +
         last_displacements_m_.capacity() * sizeof(Eigen::Vector3d) + moved_.capacity() +
         vertex_recomputed_.capacity() + is_projected_.capacity() +
         (projected_.capacity() + candidates_.capacity()) * sizeof(uint32_t) + normal_updates_.bytes() +
         restored_.capacity() * sizeof(restored_[0]);
}

double CarSkin::reachAlong_m(const std::vector<Eigen::Vector3d>& displacements_m,
                             const Eigen::Vector3d& into) const {
  // n . (v - v0) = sum_i w_i (n . d_i): with weights that are all >= 0 and sum to 1 (idw) at most the
  // largest n . d_i, else at most gain x the largest |n . d_i|.
  double largest_m = 0;
  for (const Eigen::Vector3d& d : displacements_m)
    largest_m = std::max(largest_m, build_->nonnegative_weights ? into.dot(d) : std::abs(into.dot(d)));
  return (build_->nonnegative_weights ? 1.0 : build_->displacement_gain) * largest_m +
         deform::kProjectionClearance_m;
}

Eigen::Vector3f CarSkin::skinPosition(std::size_t vertex) const {
  if (!is_projected_[vertex]) return positions_m_[vertex];
  const auto at = std::find(projected_.begin(), projected_.end(), static_cast<uint32_t>(vertex));
  return projected_from_m_[static_cast<std::size_t>(at - projected_.begin())];
}

double CarSkin::displacementBound_m(const std::vector<Eigen::Vector3d>& displacements_m) const {
  double largest_m = 0;
  for (const Eigen::Vector3d& d : displacements_m) largest_m = std::max(largest_m, d.norm());
  return build_->displacement_gain * largest_m + deform::kProjectionClearance_m;
}

std::size_t CarSkin::update(const std::vector<Eigen::Vector3d>& displacements_m) {
  return update(displacements_m, {});
}

std::size_t CarSkin::update(const std::vector<Eigen::Vector3d>& displacements_m,
                            const std::vector<deform::ContactShape>& obstacles) {
  assert(displacements_m.size() == last_displacements_m_.size());
  last_projection_ = {};
  bool any = false;
  for (std::size_t i = 0; i < displacements_m.size(); ++i) {
    moved_[i] = displacements_m[i] != last_displacements_m_[i] ? 1 : 0;
    any = any || moved_[i];
  }
  if (!any && obstacles.empty() && projected_.empty()) return 0;
  std::size_t changed = 0;
  if (any) {
    changed = build_->skin->deformMoved(build_->rest_m.data(), displacements_m.data(), moved_,
                                        positions_m_.data(), 0, &vertex_recomputed_);
    last_displacements_m_ = displacements_m;
  } else {
    vertex_recomputed_.assign(positions_m_.size(), 0);
  }
  const auto projection_start = std::chrono::steady_clock::now();
  // Back to the skin's position before the test (the skin did not recompute a vertex whose control
  // points stayed put, and its position now is the projected one).
  restored_.clear();
  for (std::size_t k = 0; k < projected_.size(); ++k) {
    const uint32_t v = projected_[k];
    is_projected_[v] = 0;
    if (vertex_recomputed_[v]) continue;
    restored_.emplace_back(v, positions_m_[v]);
    positions_m_[v] = projected_from_m_[k];
    vertex_recomputed_[v] = 1;
    ++changed;
  }
  projected_.clear();
  projected_from_m_.clear();
  const double reach_m = obstacles.empty() ? 0 : displacementBound_m(displacements_m);
  for (const deform::ContactShape& shape : obstacles) {
    candidates_.clear();
    // The ground (or any half-space): only a vertex that moved into it can be in it, so the reach is the
    // points' largest motion along its inward normal, not their largest motion: after a frontal crash a
    // few centimetres of sag, not the 0.5 m the front moved back (10,000 of 20,000 vertices tested in
    // wall_crash's busiest frames before).
    const auto* ground = std::get_if<deform::HalfSpaceShape>(&shape);
    const double shape_reach_m =
        ground ? std::min(reach_m, reachAlong_m(displacements_m, -ground->normal.normalized())) : reach_m;
    deform::verticesNear(shape, build_->grid, shape_reach_m, candidates_);
    last_projection_.tested += candidates_.size();
    if (std::holds_alternative<deform::HalfSpaceShape>(shape))
      last_projection_.tested_ground += candidates_.size();
    for (const uint32_t v : candidates_) {
      Eigen::Vector3d x = positions_m_[v].cast<double>();
      if (!deform::projectOutOf(shape, build_->interior_m, x)) continue;
      if (!is_projected_[v]) {
        is_projected_[v] = 1;
        projected_.push_back(v);
        projected_from_m_.push_back(positions_m_[v]);
        ++last_projection_.projected;
        if (!vertex_recomputed_[v]) ++changed;
        vertex_recomputed_[v] = 1;
      }
      positions_m_[v] = x.cast<float>();
    }
  }
  // A vertex put back and projected again to the very same place did not change (a car resting against a
  // wall re-uploads nothing).
  for (const auto& [v, before] : restored_)
    if (positions_m_[v] == before) {
      vertex_recomputed_[v] = 0;
      --changed;
    }
  last_projection_.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - projection_start).count();
  if (changed == 0 && !any) return 0;
  if (!normals_computed_) {
    normal_updates_.computeAll(positions_m_, build_->triangles, normals_);
    normals_computed_ = true;
  } else {
    normal_updates_.update(positions_m_, build_->triangles, vertex_recomputed_, normals_);
  }
  return changed;
}

std::shared_ptr<const deform::Skin> SkinCache::get(const deform::Mesh& body,
                                                   const std::vector<Eigen::Vector3d>& control_rest_m,
                                                   const vehicle::DeformationSettings& settings) {
  const Key key{&body, &control_rest_m, settings.alpha, settings.k_nearest,
                static_cast<int>(settings.skin_method)};
  std::shared_ptr<const deform::Skin>& skin = skins_[key];
  if (!skin) skin = CarSkin::buildSkin(body, control_rest_m, settings);
  return skin;
}

std::shared_ptr<const CarSkin::Build> CarSkinBuilds::get(const deform::Mesh& body,
                                                         const std::vector<Eigen::Vector3d>& control_rest_m,
                                                         const vehicle::DeformationSettings& settings) {
  std::shared_ptr<const deform::Skin> skin = skins_.get(body, control_rest_m, settings);
  std::shared_ptr<const CarSkin::Build>& build = builds_[skin.get()];
  if (!build) build = CarSkin::share(body, std::move(skin));
  return build;
}

}  // namespace scenes
