// Area-weighted vertex normals, of the whole mesh or of the vertices near what moved.
#include <deform/mesh.hpp>

#include <cmath>

namespace deform {
namespace {

/// Twice the area times the unit normal of triangle t: summing these weights each triangle by its area.
/// One definition for the full and the partial paths, so both round alike.
inline Eigen::Vector3d triangleAreaNormal(const Mesh& mesh, const Triangle& t) {
  const Eigen::Vector3d a = mesh.positions_m[t[0]].cast<double>();
  const Eigen::Vector3d b = mesh.positions_m[t[1]].cast<double>();
  const Eigen::Vector3d c = mesh.positions_m[t[2]].cast<double>();
  return (b - a).cross(c - a);
}

inline Eigen::Vector3f unitOrUp(const Eigen::Vector3d& sum) {
  const double len = sum.norm();
  return len > 0 ? (sum / len).cast<float>() : Eigen::Vector3f(0, 0, 1);
}

}  // namespace

void computeVertexNormals(Mesh& mesh) {
  // Scattered in triangle order: each vertex's sum takes its triangles in increasing order, as below.
  std::vector<Eigen::Vector3d> sum(mesh.positions_m.size(), Eigen::Vector3d::Zero());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d area_normal = triangleAreaNormal(mesh, t);
    for (uint32_t v : t) sum[v] += area_normal;
  }
  mesh.normals.resize(mesh.positions_m.size());
  for (std::size_t i = 0; i < sum.size(); ++i) mesh.normals[i] = unitOrUp(sum[i]);
}

VertexTriangles vertexTriangles(const Mesh& mesh) {
  // Counting sort by vertex; filling in triangle order keeps each vertex's list in increasing order.
  VertexTriangles around;
  around.begin.assign(mesh.positions_m.size() + 1, 0);
  for (const auto& t : mesh.triangles)
    for (uint32_t v : t) ++around.begin[v + 1];
  for (std::size_t v = 0; v < mesh.positions_m.size(); ++v) around.begin[v + 1] += around.begin[v];
  around.triangle.resize(around.begin.back());
  std::vector<std::size_t> fill(around.begin.begin(), around.begin.end() - 1);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (uint32_t v : mesh.triangles[i]) around.triangle[fill[v]++] = static_cast<uint32_t>(i);
  return around;
}

void updateVertexNormals(Mesh& mesh, const VertexTriangles& around, const std::vector<uint32_t>& vertices) {
  for (uint32_t v : vertices) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t s = around.begin[v]; s < around.begin[v + 1]; ++s)
      sum += triangleAreaNormal(mesh, mesh.triangles[around.triangle[s]]);
    mesh.normals[v] = unitOrUp(sum);
  }
}

}  // namespace deform
