#include "render/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

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
  data.closed = isClosedOutward(mesh);
  return data;
}

bool isClosedOutward(const deform::Mesh& mesh) {
  if (mesh.triangles.empty()) return false;
  // Every directed edge a->b exactly once, and the set of reversed edges b->a equal to it: two sorts
  // and a comparison, linear-logarithmic even for millions of triangles.
  std::vector<uint64_t> edges, reversed;
  edges.reserve(mesh.triangles.size() * 3);
  reversed.reserve(mesh.triangles.size() * 3);
  for (const deform::Triangle& t : mesh.triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const uint64_t a = t[k], b = t[(k + 1) % 3];
      edges.push_back(a << 32 | b);
      reversed.push_back(b << 32 | a);
    }
  }
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  std::sort(reversed.begin(), reversed.end());
  if (edges != reversed) return false;
  // Outward: the divergence theorem gives a positive volume for outward winding.
  double six_volume = 0.0;
  for (const deform::Triangle& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions_m[t[0]].cast<double>(),
                          b = mesh.positions_m[t[1]].cast<double>(),
                          c = mesh.positions_m[t[2]].cast<double>();
    six_volume += a.dot(b.cross(c));
  }
  return six_volume > 0.0;
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
