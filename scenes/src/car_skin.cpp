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

CarSkin::CarSkin(const deform::Mesh& body, const std::vector<Eigen::Vector3d>& control_rest_m,
                 const vehicle::DeformationSettings& settings)
    : CarSkin(body, buildSkin(body, control_rest_m, settings)) {}

CarSkin::CarSkin(const deform::Mesh& body, std::shared_ptr<const deform::Skin> skin)
    : skin_(std::move(skin)),
      rest_m_(body.positions_m),
      mesh_(body),
      last_displacements_m_(skin_->controlPointCount(), Eigen::Vector3d::Zero()),
      moved_(skin_->controlPointCount(), 0),
      normals_(body),
      grid_(body.positions_m),
      is_projected_(body.positions_m.size(), 0) {
  if (mesh_.normals.size() != mesh_.positions_m.size()) {
    normals_.computeAll(mesh_);
    normals_computed_ = true;
  }
  interior_m_ = 0.5 * (grid_.bounds().min_m + grid_.bounds().max_m);
  // v - v0 = sum_i w_i d_i, so |v - v0| <= (sum_i |w_i|) max_i |d_i|: 1 for idw, more for mls's
  // negative weights.
  for (std::size_t j = 0; j < skin_->vertexCount(); ++j) {
    double gain = 0;
    for (std::size_t k = 0; k < skin_->influences(); ++k) {
      gain += std::abs(skin_->slotWeight(j, k));
      nonnegative_weights_ = nonnegative_weights_ && skin_->slotWeight(j, k) >= 0;
    }
    displacement_gain_ = std::max(displacement_gain_, gain);
  }
}

double CarSkin::reachAlong_m(const std::vector<Eigen::Vector3d>& displacements_m,
                             const Eigen::Vector3d& into) const {
  // n . (v - v0) = sum_i w_i (n . d_i): with weights that are all >= 0 and sum to 1 (idw) at most the
  // largest n . d_i, else at most gain x the largest |n . d_i|.
  double largest_m = 0;
  for (const Eigen::Vector3d& d : displacements_m)
    largest_m = std::max(largest_m, nonnegative_weights_ ? into.dot(d) : std::abs(into.dot(d)));
  return (nonnegative_weights_ ? 1.0 : displacement_gain_) * largest_m + deform::kProjectionClearance_m;
}

Eigen::Vector3f CarSkin::skinPosition(std::size_t vertex) const {
  if (!is_projected_[vertex]) return mesh_.positions_m[vertex];
  const auto at = std::find(projected_.begin(), projected_.end(), static_cast<uint32_t>(vertex));
  return projected_from_m_[static_cast<std::size_t>(at - projected_.begin())];
}

double CarSkin::displacementBound_m(const std::vector<Eigen::Vector3d>& displacements_m) const {
  double largest_m = 0;
  for (const Eigen::Vector3d& d : displacements_m) largest_m = std::max(largest_m, d.norm());
  return displacement_gain_ * largest_m + deform::kProjectionClearance_m;
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
    changed = skin_->deformMoved(rest_m_.data(), displacements_m.data(), moved_, mesh_.positions_m.data(), 0,
                                 &vertex_recomputed_);
    last_displacements_m_ = displacements_m;
  } else {
    vertex_recomputed_.assign(mesh_.positions_m.size(), 0);
  }
  const auto projection_start = std::chrono::steady_clock::now();
  // Back to the skin's position before the test (the skin did not recompute a vertex whose control
  // points stayed put, and its position now is the projected one).
  restored_.clear();
  for (std::size_t k = 0; k < projected_.size(); ++k) {
    const uint32_t v = projected_[k];
    is_projected_[v] = 0;
    if (vertex_recomputed_[v]) continue;
    restored_.emplace_back(v, mesh_.positions_m[v]);
    mesh_.positions_m[v] = projected_from_m_[k];
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
    deform::verticesNear(shape, grid_, shape_reach_m, candidates_);
    last_projection_.tested += candidates_.size();
    if (std::holds_alternative<deform::HalfSpaceShape>(shape))
      last_projection_.tested_ground += candidates_.size();
    for (const uint32_t v : candidates_) {
      Eigen::Vector3d x = mesh_.positions_m[v].cast<double>();
      if (!deform::projectOutOf(shape, interior_m_, x)) continue;
      if (!is_projected_[v]) {
        is_projected_[v] = 1;
        projected_.push_back(v);
        projected_from_m_.push_back(mesh_.positions_m[v]);
        ++last_projection_.projected;
        if (!vertex_recomputed_[v]) ++changed;
        vertex_recomputed_[v] = 1;
      }
      mesh_.positions_m[v] = x.cast<float>();
    }
  }
  // A vertex put back and projected again to the very same place did not change (a car resting against a
  // wall re-uploads nothing).
  for (const auto& [v, before] : restored_)
    if (mesh_.positions_m[v] == before) {
      vertex_recomputed_[v] = 0;
      --changed;
    }
  last_projection_.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - projection_start).count();
  if (changed == 0 && !any) return 0;
  if (!normals_computed_) {
    normals_.computeAll(mesh_);
    normals_computed_ = true;
  } else {
    normals_.update(mesh_, vertex_recomputed_);
  }
  return changed;
}

}  // namespace scenes
