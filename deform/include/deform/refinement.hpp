#pragma once
// Refinement of a body's control surface at run time (issue "Resolution where and when the car is hit").
// The surface is a red-green hierarchy over the start level's triangles (Bank, Sherman & Weiser 1983):
// a triangle asked for splits into four (red), a neighbour with two or three split edges splits too, and
// one with a single split edge is halved (green), so the surface is always a closed, conforming
// 2-manifold, graded (triangles that share an edge differ by at most one level). Red-green, not a
// hierarchy refined at load: the finest level a contact needs is known only when it comes, and the green
// halves are rebuilt from the red leaves on every refinement, so they never nest.
//
// A refinement adds points only, at the midpoints of edges; a point's index never changes. The body
// moves onto the finer surface by transferBody: positions, rest places and velocities by interpolation,
// and the plastic rest shape from each coarse triangle's own rest metric, so a dent keeps its shape
// (Narain, Pfaff & O'Brien 2013, "Folding and crumpling adaptive sheets", keep the plastic embedding
// for the same reason).
#include <deform/body_settings.hpp>
#include <deform/body_state.hpp>
#include <deform/contact_shapes.hpp>
#include <deform/control_mesh.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

namespace deform {

/// The index that names nothing: no parent, no children, no midpoint, no owner (UINT32_MAX).
inline constexpr uint32_t kNoIndex = UINT32_MAX;

/// The red tree over a closed control surface, and the points its splits added.
class SurfaceHierarchy {
 public:
  /// A triangle of the tree: a start triangle (level 0) or one of the four of a red split.
  struct Node {
    std::array<uint32_t, 3> corners{};  ///< control points, outward (CCW) winding
    uint32_t parent = UINT32_MAX;       ///< UINT32_MAX at level 0
    uint32_t first_child =
        UINT32_MAX;  ///< its four children are first_child .. first_child + 3; none: a leaf
    uint32_t level = 0;
  };
  /// How big the hierarchy was: every node and point below these counts existed then.
  struct Mark {
    std::size_t nodes = 0, points = 0;
  };

  /// The start level: every triangle of `base` a leaf. Throws InputError when `base` is not a closed
  /// 2-manifold (an edge not shared by exactly two triangles of opposite direction).
  explicit SurfaceHierarchy(const ControlMesh& base);

  const std::vector<Node>& nodes() const { return nodes_; }
  /// Rest position of every point: the base's, then each added point at the midpoint of its edge [m].
  const std::vector<Eigen::Vector3d>& restPoints() const { return rest_points_m_; }
  std::size_t basePointCount() const { return base_points_; }
  /// The edge point `p` halves (p >= basePointCount()).
  std::array<uint32_t, 2> parentsOf(uint32_t p) const { return parents_[p - base_points_]; }
  /// The point halving edge a-b, or UINT32_MAX when it has not been split.
  uint32_t midpoint(uint32_t a, uint32_t b) const;
  /// The nodes split, in the order they were (replaying them rebuilds the hierarchy).
  const std::vector<uint32_t>& splitOrder() const { return split_order_; }
  Mark mark() const { return {nodes_.size(), rest_points_m_.size()}; }
  bool isLeaf(uint32_t node) const { return nodes_[node].first_child == UINT32_MAX; }

  /// Splits leaf `node` into four, first splitting any coarser neighbour (grading) and afterwards any
  /// neighbour left with two or three split edges (closure). False, and nothing changed, when that would
  /// take the points past `max_points` or `node` is not a leaf.
  bool split(uint32_t node, std::size_t max_points);

  /// The conforming surface: each leaf as it is, or halved from its split edge's point to the opposite
  /// corner (green). `leaf_of` (optional) gets, per triangle, the leaf it lies in.
  std::vector<std::array<uint32_t, 3>> triangles(std::vector<uint32_t>* leaf_of = nullptr) const;
  /// The same at `then`: the hierarchy as it was when mark() returned it.
  std::vector<std::array<uint32_t, 3>> triangles(Mark then, std::vector<uint32_t>* leaf_of = nullptr) const;

 private:
  bool splitGraded(uint32_t node, std::size_t max_points);
  /// The leaf across edge k (corner k to k + 1) of leaf `node`: of its level, or one level coarser.
  uint32_t across(uint32_t node, int k) const;
  uint32_t addMidpoint(uint32_t a, uint32_t b);
  uint32_t ownerOf(uint32_t a, uint32_t b) const;  ///< the node with directed edge a->b, or UINT32_MAX

  std::vector<Node> nodes_;
  std::vector<Eigen::Vector3d> rest_points_m_;
  std::size_t base_points_ = 0;
  std::vector<std::array<uint32_t, 2>> parents_;
  std::vector<uint32_t> split_order_;
  // Directed edge (a << 32 | b) -> the node that has it; undirected (min << 32 | max) -> its midpoint.
  std::unordered_map<uint64_t, uint32_t> edge_owner_, edge_midpoint_;
};

/// A body moved onto a finer surface.
struct TransferredBody {
  std::shared_ptr<const BodySettings> settings;
  BodyState state;
};

/// Moves a body whose surface was `hierarchy` at `before` onto the hierarchy as it is now. `description`
/// is the one the body was built with: createBodySettings builds the constraints on the finer surface, so
/// each one's stiffness and yield stand for the skin it now covers. The core (its place and mass) stays.
/// - A new point starts at the midpoint of its edge's two points, at their mean velocity, its column's
///   rest place at the mean of theirs.
/// - Every point whose patch changed takes the tetrahedral fan's mass on the finer surface, tilted by the
///   least linear field that keeps their mass and first moment; their velocities then shift and turn
///   together to give back the momentum and angular momentum. Mass, centre of mass, momentum and angular
///   momentum are unchanged to rounding.
/// - A new edge's rest length is the distance between its ends laid out flat in the coarse triangle it
///   lies in, by that triangle's current rest lengths; a new bend's keeps the fold of the coarse hinge it
///   lies on; a spoke keeps its stretch. A body at rest stays at rest with no elastic energy.
TransferredBody transferBody(const SurfaceHierarchy& hierarchy, SurfaceHierarchy::Mark before,
                             const BodySettings& settings, const BodyState& state,
                             const BodyDescription& description);

/// The settings of a body on the hierarchy's surface now with these point masses (one per point): what
/// transferBody built, for a saved refined body (its masses depend on the order its refinements came in,
/// the rest on the surface alone). `start` is the body at the hierarchy's base. Throws InputError for a
/// count that does not match.
std::shared_ptr<const BodySettings> refinedSettings(const SurfaceHierarchy& hierarchy,
                                                    const BodySettings& start,
                                                    const BodyDescription& description,
                                                    const std::vector<double>& point_mass_kg);

/// When a contact asks for a finer surface (splitNearContacts).
struct ContactRefinement {
  /// A leaf near an obstacle splits while its longest edge is above this share of the obstacle's radius of
  /// curvature where it meets the leaf [1].
  double edge_per_radius = 0.5;
  /// ... and not below this floor [m] (scene key vehicle.deformation.contact_edge_m): a leaf splits only if
  /// its children's longest edges stay at least this long, so the longest edges near a contact end between
  /// the floor and twice it.
  double contact_edge_m = 0.05;
  /// How near an obstacle must come to a leaf to count [m]: the step's relative travel and a margin.
  double reach_m = 0.1;
  std::size_t max_points = 2000;  ///< the bound (scene key vehicle.deformation.max_control_points)
};

/// What splitNearContacts did.
struct RefinementOutcome {
  std::size_t splits = 0;  ///< leaves split (the grading and closure they needed not counted)
  bool bounded = false;    ///< a split was refused: it would have passed max_points
};

/// Splits every leaf that one of `shapes` comes within reach of, while its longest edge at rest is longer
/// than the rule allows for the obstacle's local radius of curvature there, found from the obstacle's surface
/// points and normals nearest seven points of the leaf (its corners, edge midpoints and centroid): a flat
/// wall has none (no split), a pole its radius, a box's edge or another car's corner next to none (split to
/// the floor). `positions_m` are the points where the body has them now (vehicle frame, as the shapes); the
/// points a split adds are appended at their edges' midpoints.
RefinementOutcome splitNearContacts(SurfaceHierarchy& hierarchy, std::vector<Eigen::Vector3d>& positions_m,
                                    const std::vector<ContactShape>& shapes, const ContactRefinement& rule);

}  // namespace deform
