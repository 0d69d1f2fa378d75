#include "render/scene.hpp"

#include <algorithm>
#include <cmath>

namespace sandbox::render {

MeshData meshData(const deform::Mesh& mesh, const Eigen::Vector3f& base_colour) {
  MeshData data;
  data.positions_m = mesh.positions_m;
  data.triangles = mesh.triangles;
  if (mesh.normals.size() == mesh.positions_m.size()) {
    data.normals = mesh.normals;
  } else {
    deform::Mesh copy = mesh;
    deform::computeVertexNormals(copy);
    data.normals = std::move(copy.normals);
  }
  data.base_colour = base_colour;
  return data;
}

Environment environmentAround(const deform::Aabb& box) {
  Environment environment;
  const double diagonal = box.diagonal_m();
  environment.ground.height_m = static_cast<float>(box.min_m.z());
  environment.ground.centre_m = ((box.min_m + box.max_m) * 0.5).head<2>().cast<float>();
  environment.ground.radius_m = static_cast<float>(std::max(diagonal, 1e-3) * 12.0);
  environment.ground.grid_spacing_m = gridSpacingFor(diagonal);
  return environment;
}

float gridSpacingFor(double diagonal_m) {
  if (!(diagonal_m > 0)) return 1.0f;
  return static_cast<float>(std::pow(10.0, std::floor(std::log10(diagonal_m / 2.0))));
}

}  // namespace sandbox::render
