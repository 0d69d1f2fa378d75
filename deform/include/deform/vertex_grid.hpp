#pragma once
// A uniform grid over a mesh's rest positions, built once: the vertices near an obstacle are found by
// the cells its bounding box overlaps, so a per-frame query costs the contact region, not the mesh.
#include <deform/mesh.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace deform {

/// Rest positions bucketed in cubic cells, for the vertices near a box.
class VertexGrid {
 public:
  VertexGrid() = default;
  /// About `per_cell` rest positions to a cell on average (cubic cells over their bounding box).
  explicit VertexGrid(const std::vector<Eigen::Vector3f>& rest_m, double per_cell = 8);
  /// The same over double positions (the control mesh's candidates, deform/src/control_mesh_lod.cpp).
  explicit VertexGrid(const std::vector<Eigen::Vector3d>& rest_m, double per_cell = 8);

  /// Appends to `out` every vertex whose rest position lies in a cell overlapping `box` (a superset of
  /// those inside it); returns how many were appended.
  std::size_t query(const Aabb& box, std::vector<uint32_t>& out) const;
  /// The rest positions' bounding box [m].
  const Aabb& bounds() const { return bounds_; }
  std::size_t vertexCount() const { return vertices_.size(); }
  /// Heap bytes held.
  std::size_t bytes() const { return (cell_begin_.capacity() + vertices_.capacity()) * sizeof(uint32_t); }

 private:
  Aabb bounds_;
  double cell_m_ = 1;                 ///< edge of a cubic cell [m]
  Eigen::Vector3i cells_{0, 0, 0};    ///< cells along each axis
  std::vector<uint32_t> cell_begin_;  ///< vertices of cell c: vertices_[cell_begin_[c] .. [c + 1])
  std::vector<uint32_t> vertices_;    ///< vertex indices, cell-major
  Eigen::Vector3i cellOf(const Eigen::Vector3d& p_m) const;
  template <class Point>
  void build(const std::vector<Point>& rest_m, double per_cell);
};

}  // namespace deform
