#pragma once
// Vertex normals kept up to date as a mesh's vertices move (DESIGN.md section 8: only what moved is
// recomputed): an update recomputes the normals of the vertices that share a triangle with a moved one.
// The triangles around each vertex are fixed by the mesh and shared by every copy of it (the cars of one
// build); a copy keeps only its positions, its normals and a flag per vertex.
#include <deform/mesh.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace deform {

/// The triangles around each vertex of a mesh, in increasing order (a triangle naming a vertex twice is
/// listed twice, as computeVertexNormals adds it twice). Immutable once built.
class VertexTriangles {
 public:
  VertexTriangles(const std::vector<Triangle>& triangles, std::size_t vertex_count);
  std::size_t vertexCount() const { return around_begin_.size() - 1; }
  const uint32_t* begin(std::size_t vertex) const { return triangle_.data() + around_begin_[vertex]; }
  const uint32_t* end(std::size_t vertex) const { return triangle_.data() + around_begin_[vertex + 1]; }
  std::size_t bytes() const;  ///< heap bytes held

 private:
  std::vector<uint32_t> around_begin_;  ///< vertex v's triangles: triangle_[around_begin_[v] .. [v + 1])
  std::vector<uint32_t> triangle_;
};

/// Partial normal updates of one copy of a mesh.
class VertexNormals {
 public:
  /// For `mesh` alone (its own VertexTriangles).
  explicit VertexNormals(const Mesh& mesh);
  /// For a copy of the mesh whose triangles `around` was built from (shared).
  explicit VertexNormals(std::shared_ptr<const VertexTriangles> around);

  /// Every normal from the triangles, bit-identical to computeVertexNormals.
  void computeAll(const std::vector<Eigen::Vector3f>& positions_m, const std::vector<Triangle>& triangles,
                  std::vector<Eigen::Vector3f>& normals) const;
  void computeAll(Mesh& mesh) const { computeAll(mesh.positions_m, mesh.triangles, mesh.normals); }

  /// After the vertices flagged in `moved` (one flag per vertex) moved: the normals of every vertex
  /// sharing a triangle with one of them, bit-identical to computeVertexNormals (the same area normals
  /// summed in the same order: each vertex's triangles in increasing order). `normals` must hold one per
  /// vertex (computeAll once). Returns the normals recomputed.
  std::size_t update(const std::vector<Eigen::Vector3f>& positions_m, const std::vector<Triangle>& triangles,
                     const std::vector<uint8_t>& moved, std::vector<Eigen::Vector3f>& normals);
  std::size_t update(Mesh& mesh, const std::vector<uint8_t>& moved) {
    return update(mesh.positions_m, mesh.triangles, moved, mesh.normals);
  }

  /// Heap bytes of this copy's own (not the shared VertexTriangles).
  std::size_t bytes() const {
    return stale_vertex_.capacity() + stale_vertices_.capacity() * sizeof(uint32_t);
  }

 private:
  std::shared_ptr<const VertexTriangles> around_;
  std::vector<uint8_t> stale_vertex_;     ///< scratch, all 0 between updates
  std::vector<uint32_t> stale_vertices_;  ///< scratch
};

}  // namespace deform
