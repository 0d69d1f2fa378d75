#include <scenes/car_skin.hpp>

#include <cassert>

namespace scenes {

CarSkin::CarSkin(const deform::Mesh& body, const std::vector<Eigen::Vector3d>& control_rest_m,
                 const vehicle::DeformationSettings& settings)
    : skin_(deform::Skin::build(body.positions_m, control_rest_m,
                                {settings.alpha, settings.k_nearest, 0, settings.skin_method})),
      rest_m_(body.positions_m),
      mesh_(body),
      last_displacements_m_(control_rest_m.size(), Eigen::Vector3d::Zero()),
      moved_(control_rest_m.size(), 0),
      normals_(body) {
  if (mesh_.normals.size() != mesh_.positions_m.size()) {
    normals_.computeAll(mesh_);
    normals_computed_ = true;
  }
}

std::size_t CarSkin::update(const std::vector<Eigen::Vector3d>& displacements_m) {
  assert(displacements_m.size() == last_displacements_m_.size());
  bool any = false;
  for (std::size_t i = 0; i < displacements_m.size(); ++i) {
    moved_[i] = displacements_m[i] != last_displacements_m_[i] ? 1 : 0;
    any = any || moved_[i];
  }
  if (!any) return 0;
  const std::size_t recomputed = skin_.deformMoved(rest_m_.data(), displacements_m.data(), moved_,
                                                   mesh_.positions_m.data(), 0, &vertex_recomputed_);
  last_displacements_m_ = displacements_m;
  if (!normals_computed_) {
    normals_.computeAll(mesh_);
    normals_computed_ = true;
  } else {
    normals_.update(mesh_, vertex_recomputed_);
  }
  return recomputed;
}

}  // namespace scenes
