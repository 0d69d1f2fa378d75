// Area-weighted vertex normals, of the whole mesh or of the vertices around what moved.
#include <deform/vertex_normals.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace deform {
namespace {

/// Twice the area times the unit normal of triangle t: summing these weights each triangle by its area.
/// One definition for every path, so all round alike.
inline Eigen::Vector3d triangleAreaNormal(const std::vector<Eigen::Vector3f>& positions_m,
                                          const Triangle& t) {
  const Eigen::Vector3d a = positions_m[t[0]].cast<double>();
  const Eigen::Vector3d b = positions_m[t[1]].cast<double>();
  const Eigen::Vector3d c = positions_m[t[2]].cast<double>();
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
    const Eigen::Vector3d area_normal = triangleAreaNormal(mesh.positions_m, t);
    for (uint32_t v : t) sum[v] += area_normal;
  }
  mesh.normals.resize(mesh.positions_m.size());
  for (std::size_t i = 0; i < sum.size(); ++i) mesh.normals[i] = unitOrUp(sum[i]);
}

VertexTriangles::VertexTriangles(const std::vector<Triangle>& triangles, std::size_t vertex_count) {
  // Counting sort by vertex; filling in triangle order keeps each vertex's list in increasing order.
  around_begin_.assign(vertex_count + 1, 0);
  for (const auto& t : triangles)
    for (uint32_t v : t) ++around_begin_[v + 1];
  for (std::size_t v = 0; v < vertex_count; ++v) around_begin_[v + 1] += around_begin_[v];
  triangle_.resize(around_begin_.back());
  std::vector<uint32_t> fill(around_begin_.begin(), around_begin_.end() - 1);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (uint32_t v : triangles[i]) triangle_[fill[v]++] = static_cast<uint32_t>(i);
}

std::size_t VertexTriangles::bytes() const {
  return (around_begin_.capacity() + triangle_.capacity()) * sizeof(uint32_t);
}

VertexNormals::VertexNormals(const Mesh& mesh)
    : VertexNormals(std::make_shared<const VertexTriangles>(mesh.triangles, mesh.positions_m.size())) {}

VertexNormals::VertexNormals(std::shared_ptr<const VertexTriangles> around)
    : around_(std::move(around)), stale_vertex_(around_->vertexCount(), 0) {}

void VertexNormals::computeAll(const std::vector<Eigen::Vector3f>& positions_m,
                               const std::vector<Triangle>& triangles,
                               std::vector<Eigen::Vector3f>& normals) const {
  // Each triangle's area normal once, held only for this pass.
  std::vector<Eigen::Vector3d> area_normal_m2(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    area_normal_m2[t] = triangleAreaNormal(positions_m, triangles[t]);
  normals.resize(positions_m.size());
  for (std::size_t v = 0; v < around_->vertexCount(); ++v) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const uint32_t* t = around_->begin(v); t != around_->end(v); ++t) sum += area_normal_m2[*t];
    normals[v] = unitOrUp(sum);
  }
}

std::size_t VertexNormals::update(const std::vector<Eigen::Vector3f>& positions_m,
                                  const std::vector<Triangle>& triangles, const std::vector<uint8_t>& moved,
                                  std::vector<Eigen::Vector3f>& normals) {
  stale_vertices_.clear();
  const std::size_t count = std::min(moved.size(), around_->vertexCount());
  for (std::size_t v = 0; v < count; ++v) {
    if (!moved[v]) continue;
    for (const uint32_t* t = around_->begin(v); t != around_->end(v); ++t)
      for (uint32_t corner : triangles[*t]) {
        if (!stale_vertex_[corner]) stale_vertices_.push_back(corner);
        stale_vertex_[corner] = 1;
      }
  }
  // No per-triangle cache in the copy (24 bytes per triangle in every car): each stale vertex sums its
  // triangles' area normals afresh, the same values in the same order as computeAll. (A scratch of the
  // thread's that computed each triangle once was measured no faster: it adds a lookup per triangle.)
  for (uint32_t v : stale_vertices_) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const uint32_t* t = around_->begin(v); t != around_->end(v); ++t)
      sum += triangleAreaNormal(positions_m, triangles[*t]);
    normals[v] = unitOrUp(sum);
    stale_vertex_[v] = 0;
  }
  return stale_vertices_.size();
}

}  // namespace deform
