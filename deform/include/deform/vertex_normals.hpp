#pragma once
// Vertex normals kept up to date as a mesh's vertices move (DESIGN.md section 8: only what moved is
// recomputed): each triangle's area normal is cached, an update recomputes only the triangles with a
// moved corner and then the normals of those triangles' corners.
#include <deform/mesh.hpp>

#include <cstdint>
#include <vector>

namespace deform {

/// Cached triangle normals of a mesh, for partial normal updates.
class VertexNormals {
 public:
  /// The triangles around each vertex of `mesh` (its triangles never change afterwards).
  explicit VertexNormals(const Mesh& mesh);

  /// Every normal from the triangles, bit-identical to computeVertexNormals(mesh).
  void computeAll(Mesh& mesh);

  /// After the vertices flagged in `moved` (one flag per vertex) moved: the triangles with a moved corner
  /// and the normals of their corners, bit-identical to computeVertexNormals (same area normals summed
  /// in the same order: each vertex's triangles in increasing order). computeAll must have run once.
  /// Returns the normals recomputed.
  std::size_t update(Mesh& mesh, const std::vector<uint8_t>& moved);

 private:
  /// The triangles around vertex v: triangle_[around_begin_[v] .. around_begin_[v + 1]), increasing (a
  /// triangle naming a vertex twice is listed twice, as computeVertexNormals adds it twice).
  std::vector<std::size_t> around_begin_;
  std::vector<uint32_t> triangle_;
  std::vector<Eigen::Vector3d> area_normal_m2_;  ///< per triangle: twice its area times its unit normal
  std::vector<uint8_t> stale_triangle_;          ///< scratch, all 0 between updates
  std::vector<uint8_t> stale_vertex_;            ///< scratch, all 0 between updates
  std::vector<uint32_t> stale_vertices_;         ///< scratch
};

}  // namespace deform
