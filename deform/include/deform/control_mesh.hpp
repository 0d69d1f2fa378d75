#pragma once
// The coarse control mesh: the convex hull of a vehicle mesh, reduced or refined to N control points
// (the level of detail). Kenwright 2015, section "Low-Resolution Control Mesh", Figure "Vehicle Convex
// Hull". Immutable once built; shared by every car that uses it (DESIGN.md section 4).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace deform {

/// An edge of the control mesh with the two triangles that share it: `a`-`b` is the edge, `left` and
/// `right` are the vertices opposite it in those triangles (for bending constraints).
struct ControlEdge {
  uint32_t a = 0, b = 0;
  uint32_t left = 0, right = 0;
};

/// The control mesh: the points a body deforms by, on a closed convex surface (buildControlMesh).
struct ControlMesh {
  std::vector<Eigen::Vector3d> points_m;           ///< rest positions of the control points [m]
  std::vector<std::array<uint32_t, 3>> triangles;  ///< closed convex surface, outward (CCW) winding
  std::vector<ControlEdge> edges;                  ///< every edge once, with its two wings
  /// Centre of mass of the body [m]: the centroid of its full convex hull as a uniform solid (for a
  /// control mesh too coarse to enclose that point, the centroid of the control mesh's own solid).
  Eigen::Vector3d centre_of_mass_m{0, 0, 0};
  double volume_m3 = 0;               ///< volume enclosed by the surface [m^3]
  std::size_t hull_vertex_count = 0;  ///< vertices of the full convex hull, before LOD
  /// For a body symmetric about its X-Z plane (y -> -y): the index of each point's mirror image (itself
  /// on the plane). Empty when the body is not symmetric or the method does not keep symmetry.
  std::vector<uint32_t> mirror_of;
};

/// How evenly the control points cover the surface (controlMeshStats).
struct ControlMeshStats {
  /// Radius of the largest hole: the largest distance from a point of the control surface to its
  /// nearest control point [m]. For an even spread of N points over area A it is near sqrt(A / N).
  double largest_gap_m = 0;
  double longest_edge_m = 0;   ///< longest edge between neighbouring control points [m]
  double shortest_edge_m = 0;  ///< shortest edge [m]
  double surface_area_m2 = 0;  ///< area of the control surface [m^2]
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

/// How the hull becomes N control points.
enum class LodMethod {
  /// Points spread evenly over the hull's surface (farthest-point sampling of the hull's vertices and
  /// of points added on its faces by longest-edge bisection), triangulated through their directions
  /// from the centre of mass. Every region of the body gets control points: a dent in a flat door
  /// has points to move. The default.
  Even,
  /// The paper's reduction: the hull simplified by meshoptimizer's quadric simplifier, then re-hulled,
  /// so it stays strictly convex. Keeps corners, leaves flat regions (roof, doors) with few points.
  /// Above the hull's vertex count, faces are refined by longest-edge bisection.
  Simplify,
};

/// Control mesh with `target_points` control points (4 .. 100,000), built from the convex hull of
/// `points` by `method`. Deterministic. Count within 5 % of the target (Even: exact).
ControlMesh buildControlMesh(const std::vector<Eigen::Vector3d>& points, std::size_t target_points,
                             const char* source = "mesh", LodMethod method = LodMethod::Even);

/// Farthest-point sampling of `count` of `candidates` (the even method's choice of control points): starts
/// at the candidate farthest from `centre`, then repeatedly takes the candidate farthest from everything
/// taken so far. The largest gap left is at most twice the smallest possible for that many points. Ties go
/// to the lower index (deterministic). With `mirror_of` (each candidate's mirror image), points are taken
/// with their mirror images, so a symmetric body gets a symmetric set; an odd remainder is taken on the
/// plane of symmetry. Corners first: while some candidate flagged in `corner` is at least
/// `corner_spacing_m` from everything taken, only corners are considered, so a coarse control mesh keeps
/// the body's extreme points (a box's 8 corners, a car's nose and roof line) and its volume.
/// `by_cells`: a point taken updates only the candidates nearer it than the largest gap (found by a grid),
/// and heaps give the farthest, about C log C for C candidates; false scans every candidate at every point
/// (the reference, C x count). The same result either way. Returns the indices taken, in order.
std::vector<uint32_t> farthestPoints(const std::vector<Eigen::Vector3d>& candidates, std::size_t count,
                                     const Eigen::Vector3d& centre, const std::vector<uint32_t>& mirror_of,
                                     const std::vector<char>& corner, double corner_spacing_m,
                                     bool by_cells = true);

/// Parses "even" or "simplify"; throws InputError naming `field` otherwise.
LodMethod parseLodMethod(const std::string& text, const std::string& field);

/// A closed triangulation through `points`, all of which lie on a convex surface: their convex hull,
/// with the points it drops (those inside flat faces) inserted into those faces, and Delaunay edge flips
/// inside flat regions. Every distinct point is a vertex; triangles face outward. A dropped point goes
/// into the triangle nearest it, found among those listed near it in a grid (`nearest_by_cells`; about
/// linear in the points) or among all of them (false: the reference, quadratic), with the same result.
ControlMesh triangulateOnConvexSurface(const std::vector<Eigen::Vector3d>& points,
                                       const char* source = "mesh", bool nearest_by_cells = true);

/// Gaps, edge lengths and area of `mesh`.
ControlMeshStats controlMeshStats(const ControlMesh& mesh);

/// How far the control surface falls short of the body it stands for: the largest distance from one of
/// `points` (the body's hull vertices, say) outside the closed convex surface `mesh` to it [m]; 0 when
/// the surface holds them all.
double controlSurfaceShortfall_m(const ControlMesh& mesh, const std::vector<Eigen::Vector3d>& points);

/// Volume enclosed by the closed, outward-wound surface `triangles` over `points_m` (a fan of tetrahedra
/// from the points' mean, the divergence theorem) [m^3]; with the rest points, ControlMesh::volume_m3.
double enclosedVolume_m3(const std::vector<Eigen::Vector3d>& points_m,
                         const std::vector<std::array<uint32_t, 3>>& triangles);

/// Recomputes edges (with wings), volume and centre of mass from points_m and triangles.
void finishControlMesh(ControlMesh& mesh);

/// For each triangle t and edge j (corner j to corner j + 1), at 3 t + j: the triangle sharing that edge
/// (UINT32_MAX on an open edge).
std::vector<uint32_t> triangleNeighbours(const std::vector<std::array<uint32_t, 3>>& triangles);

}  // namespace deform
