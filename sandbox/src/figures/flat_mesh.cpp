#include "flat_mesh.hpp"

namespace sandbox::figures {

deform::Mesh facetedMesh(const deform::ControlMesh& control) {
  deform::Mesh mesh;
  for (const auto& t : control.triangles) {
    const Eigen::Vector3d a = control.points_m[t[0]], b = control.points_m[t[1]], c = control.points_m[t[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    n = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
    const auto base = static_cast<uint32_t>(mesh.positions_m.size());
    for (const auto& p : {a, b, c}) {
      mesh.positions_m.push_back(p.cast<float>());
      mesh.normals.push_back(n.cast<float>());
    }
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  return mesh;
}

}  // namespace sandbox::figures
