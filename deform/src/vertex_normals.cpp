// Area-weighted vertex normals, of the whole mesh or of the vertices around what moved.
#include <deform/vertex_normals.hpp>

#include <cmath>

namespace deform {
namespace {

/// Twice the area times the unit normal of triangle t: summing these weights each triangle by its area.
/// One definition for every path, so all round alike.
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
  // Scattered in triangle order: each vertex's sum takes its triangles in increasing order.
  std::vector<Eigen::Vector3d> sum(mesh.positions_m.size(), Eigen::Vector3d::Zero());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d area_normal = triangleAreaNormal(mesh, t);
    for (uint32_t v : t) sum[v] += area_normal;
  }
  mesh.normals.resize(mesh.positions_m.size());
  for (std::size_t i = 0; i < sum.size(); ++i) mesh.normals[i] = unitOrUp(sum[i]);
}

VertexNormals::VertexNormals(const Mesh& mesh)
    : area_normal_m2_(mesh.triangles.size(), Eigen::Vector3d::Zero()),
      stale_triangle_(mesh.triangles.size(), 0),
      stale_vertex_(mesh.positions_m.size(), 0) {
  // Counting sort by vertex; filling in triangle order keeps each vertex's list in increasing order.
  around_begin_.assign(mesh.positions_m.size() + 1, 0);
  for (const auto& t : mesh.triangles)
    for (uint32_t v : t) ++around_begin_[v + 1];
  for (std::size_t v = 0; v < mesh.positions_m.size(); ++v) around_begin_[v + 1] += around_begin_[v];
  triangle_.resize(around_begin_.back());
  std::vector<std::size_t> fill(around_begin_.begin(), around_begin_.end() - 1);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (uint32_t v : mesh.triangles[i]) triangle_[fill[v]++] = static_cast<uint32_t>(i);
}

void VertexNormals::computeAll(Mesh& mesh) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    area_normal_m2_[t] = triangleAreaNormal(mesh, mesh.triangles[t]);
  mesh.normals.resize(mesh.positions_m.size());
  for (std::size_t v = 0; v + 1 < around_begin_.size(); ++v) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t s = around_begin_[v]; s < around_begin_[v + 1]; ++s)
      sum += area_normal_m2_[triangle_[s]];
    mesh.normals[v] = unitOrUp(sum);
  }
}

std::size_t VertexNormals::update(Mesh& mesh, const std::vector<uint8_t>& moved) {
  stale_vertices_.clear();
  for (std::size_t v = 0; v < moved.size() && v + 1 < around_begin_.size(); ++v) {
    if (!moved[v]) continue;
    for (std::size_t s = around_begin_[v]; s < around_begin_[v + 1]; ++s) {
      const uint32_t t = triangle_[s];
      if (stale_triangle_[t]) continue;
      stale_triangle_[t] = 1;
      area_normal_m2_[t] = triangleAreaNormal(mesh, mesh.triangles[t]);
      for (uint32_t corner : mesh.triangles[t]) {
        if (!stale_vertex_[corner]) stale_vertices_.push_back(corner);
        stale_vertex_[corner] = 1;
      }
    }
  }
  for (uint32_t v : stale_vertices_) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t s = around_begin_[v]; s < around_begin_[v + 1]; ++s) {
      sum += area_normal_m2_[triangle_[s]];
      stale_triangle_[triangle_[s]] = 0;
    }
    mesh.normals[v] = unitOrUp(sum);
    stale_vertex_[v] = 0;
  }
  return stale_vertices_.size();
}

}  // namespace deform
