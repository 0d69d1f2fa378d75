#pragma once
// The lattice a spline skin embeds its render vertices in (deform/skin.hpp, SkinMethod::spline): the
// spline is evaluated at the lattice's nodes each frame, and each vertex follows the 27 nodes around it by
// uniform quadratic B-spline weights, so that the per-frame pass keeps a fixed set of non-negative slots
// per vertex and the surface stays smooth (C1) across the cells.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace deform::detail {

/// Cells on the longest side of the vertices' bounding box; the other sides get cells of the same size.
/// On the built-in sedan (4.6 m) 32 cells of 0.14 m, 5,775 nodes. The lattice's own smoothing is then
/// under 0.5 mm RMS next to the spline's error on `sandbox tradeoff --skin-only`'s fields: the wall
/// crash's dent at 60 points 16.3 / 15.0 / 14.6 / 14.3 mm RMS with 16 / 24 / 32 / 48 cells against the
/// spline evaluated at every vertex, 14.1 mm; the crush field at 250 points 3.82 / 2.17 / 1.85 / 1.85
/// against 2.03.
inline constexpr int kLatticeCellsOnLongestSide = 32;

/// Nodes a vertex follows: 3 x 3 x 3 around it.
inline constexpr std::size_t kLatticeSlots = 27;

/// A box lattice around the vertices and each vertex's weights over its 27 nearest nodes, kept separable:
/// the weight of node (c_x - 1 + a, c_y - 1 + b, c_z - 1 + c) is wx[a] wy[b] wz[c].
struct BsplineLattice {
  std::vector<Eigen::Vector3d> nodes_m;  ///< at the cells' centres and one ring beyond; x fastest, then y, z
  uint32_t stride[3] = {1, 1, 1};        ///< node index step along x, y and z
  std::vector<uint32_t> base;            ///< per vertex: its first node, (c_x - 1, c_y - 1, c_z - 1)
  std::vector<float> axis_weights;  ///< 9 per vertex: wx[0..2], wy[0..2], wz[0..2], each >= 0 summing to 1
};

/// The lattice of `vertices_m`: their bounding box, grown by a thousandth of its longest side, in cubic
/// cells, kLatticeCellsOnLongestSide along the longest side (at least one along each). A vertex at t cells
/// along an axis (t = c + f, 0 <= f < 1) weighs the nodes c - 1, c, c + 1 by (1 - f)^2 / 2, 1/2 + f (1 - f)
/// and f^2 / 2, the uniform quadratic B-spline (de Boor 1978, "A Practical Guide to Splines"), with node j
/// at the centre of cell j: the weights' first moment is then the vertex itself, so an affine map of the
/// nodes moves the vertex by that map, and the surface is continuously differentiable across the cells.
BsplineLattice bsplineLattice(const std::vector<Eigen::Vector3f>& vertices_m);

}  // namespace deform::detail
