#pragma once
// The coarse control mesh: the convex hull of a vehicle mesh, reduced or refined to N control points
// (the level of detail). Kenwright 2015, section "Low-Resolution Control Mesh", Figure "Vehicle Convex
// Hull". Immutable once built; shared by every car that uses it (DESIGN.md section 4).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

namespace deform {

/// An edge of the control mesh with the two triangles that share it: `a`-`b` is the edge, `left` and
/// `right` are the vertices opposite it in those triangles (for bending constraints).
struct ControlEdge {
  uint32_t a = 0, b = 0;
  uint32_t left = 0, right = 0;
};

struct ControlMesh {
  std::vector<Eigen::Vector3d> points_m;           ///< rest positions of the control points [m]
  std::vector<std::array<uint32_t, 3>> triangles;  ///< closed convex surface, outward (CCW) winding
  std::vector<ControlEdge> edges;                  ///< every edge once, with its two wings
  Eigen::Vector3d centre_of_mass_m{0, 0, 0};       ///< centroid of the solid hull (uniform density) [m]
  double volume_m3 = 0;                            ///< volume enclosed by the surface [m^3]
  std::size_t hull_vertex_count = 0;               ///< vertices of the full convex hull, before LOD
};

struct ControlMeshStats {
  double largest_gap_m = 0;   ///< longest edge between neighbouring control points [m]
  double smallest_gap_m = 0;  ///< shortest edge [m]
};

/// How a hull facet with 4 or more coplanar corners becomes triangles.
enum class FacetSplit {
  CentroidFan,  ///< add the facet's centroid as a control point and fan from it (keeps symmetry)
  Diagonals,    ///< qhull's triangulation: no new points, an arbitrary choice of diagonals
};

/// Convex hull of `points` (qhull), as a closed triangulated surface with outward winding.
/// Throws InputError (message starts with `source`) for fewer than 4 distinct points or a flat or
/// collinear set.
ControlMesh convexHull(const std::vector<Eigen::Vector3d>& points, const char* source = "mesh",
                       FacetSplit split = FacetSplit::CentroidFan);

/// Control mesh with `target_points` control points (4 .. 100,000): the hull simplified
/// (meshoptimizer, then re-hulled) when the hull has more vertices, refined by longest-edge bisection of
/// its faces when it has fewer. Deterministic. Count within 5 % of the target.
ControlMesh buildControlMesh(const std::vector<Eigen::Vector3d>& points, std::size_t target_points,
                             const char* source = "mesh");

ControlMeshStats controlMeshStats(const ControlMesh& mesh);

/// Recomputes edges (with wings), volume and centre of mass from points_m and triangles.
void finishControlMesh(ControlMesh& mesh);

}  // namespace deform
