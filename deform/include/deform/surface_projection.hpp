#pragma once
// Render vertices kept out of what the car hit (a render-mesh concern: physics never sees it). The
// control points are kept out by the body's contacts; between them the skin lets a thin post or a
// corner show through, and a front dented against a wall waves in and out of it. After the skin, a
// vertex found inside an obstacle is moved onto its surface.
#include <deform/contact_shapes.hpp>
#include <deform/mesh.hpp>
#include <deform/vertex_grid.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace deform {

/// Below this a stored float position may round back inside: a float near 4 m is spaced 4.8e-7 m, so a
/// vertex projected exactly onto the surface is left this far outside it [m].
constexpr double kProjectionClearance_m = 1e-6 * 0.5;

/// The obstacle's axis-aligned bounding box (its frame) [m]; for a half-space, the part of `clip` that
/// is within `reach_m` of it (conservative: a box holding that part). False when nothing is left.
bool shapeBounds(const ContactShape& shape, const Aabb& clip, double reach_m, Aabb& out);

/// Moves `point_m`, when inside `shape`, onto its surface (plus kProjectionClearance_m) on the side of
/// `interior_m` (a point of the car inside its body, outside the obstacle): by the shortest way out when
/// that leaves toward the interior's side (normal . (interior - point) >= 0; exact for the primitives),
/// else where the segment from the point to the interior leaves the shape (bisection, to 2^-40 of it):
/// the shortest way out of a thin post can be its far side, which would pull the skin through it.
/// Returns whether the point moved.
bool projectOutOf(const ContactShape& shape, const Eigen::Vector3d& interior_m, Eigen::Vector3d& point_m);

/// The vertices whose rest position (in `grid`) is in a cell overlapping `shape`'s bounds grown by
/// `reach_m`, the most any vertex has moved from its rest position [m]: only these can be inside it.
void verticesNear(const ContactShape& shape, const VertexGrid& grid, double reach_m,
                  std::vector<uint32_t>& out);

}  // namespace deform
