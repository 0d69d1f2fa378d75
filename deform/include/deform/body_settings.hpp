#pragma once
// The immutable part of a deformable body (DESIGN.md section 4, as Jolt's SoftBodySharedSettings):
// built once from a control mesh and its mass split, shared by every car that uses it.
#include <deform/constraints.hpp>
#include <deform/control_mesh.hpp>
#include <deform/masses.hpp>
#include <deform/material.hpp>
#include <deform/mesh.hpp>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace deform {

/// A part of the car with its own material (a soft bumper, stiff roof pillars). A control point belongs
/// to the region when it lies in `box_m` (vehicle frame) or is listed in `points`. A constraint takes
/// the material of the last region holding all its control points (the core never counts); others keep
/// the body's default.
struct MaterialRegion {
  Material material;             ///< the region's material
  std::optional<Aabb> box_m;     ///< selection box in the vehicle frame [m]; none = by index only
  std::vector<uint32_t> points;  ///< control points selected by index
  /// Visual-constraint radius for the region's points [m]; NaN keeps the body's value.
  double max_deviation_m = std::numeric_limits<double>::quiet_NaN();
};

/// What a body is made of, besides its control mesh and masses.
struct BodyDescription {
  Material material;                    ///< default material of every constraint
  std::vector<MaterialRegion> regions;  ///< later regions win over earlier ones
  /// Visual constraint (Kenwright 2015): no control point moves further than this from where it started
  /// [m]. Finite and > 0.
  double max_deviation_m = 0.3;
  /// Bends are made only across hinges folded at least this much from flat (angle between the two
  /// triangles' normals) [rad]: a distance bend across a flatter hinge is ill-conditioned and useless.
  double min_bend_fold_rad = 0.2;
  /// Crush columns held at a rest place (plasticColumnRest) instead of a rest length along the spoke.
  bool anchored_columns = false;
  /// Per-point overrides of max_deviation_m, (control point, radius [m]); applied after the regions.
  std::vector<std::pair<uint32_t, double>> max_deviation_overrides;
};

/// The immutable part of a body (createBodySettings): rest shape, masses, constraints and their material
/// constants. Shared (std::shared_ptr) by every body built from the same mesh and description.
struct BodySettings {
  std::vector<Eigen::Vector3d> rest_positions_m;  ///< control points where they started, x0 [m]
  Eigen::Vector3d core_m{0, 0, 0};                ///< the rigid core (centre of mass), vehicle frame [m]
  std::vector<double> mass_kg;                    ///< point masses from the tetrahedral fan [kg]
  std::vector<double> inverse_mass_per_kg;        ///< 1 / mass [1/kg]
  double core_mass_kg = 0;                        ///< the core's share (infinite in the solver) [kg]
  std::vector<double> max_deviation_m;            ///< visual-constraint radius per point [m]
  /// Inverse of the shell's inertia about the core, sum m (|r|^2 I - r r^T) with r = x0 - core, for the
  /// shell orientation constraint (shellRotation, turnShell) [1/(kg m^2)].
  Eigen::Matrix3d shell_inverse_inertia = Eigen::Matrix3d::Zero();

  /// The pair constraints are in sweep order, not the control mesh's: edges[0 .. edge_half_end[0]) join
  /// points of one half of the body, edges[edge_half_end[0] .. edge_half_end[1]) points of the other, and
  /// the rest cross between them; within each part, neighbours in the array share no point where they
  /// can (deform/src/sweep_order.hpp). The same for the bends' wing points.
  std::vector<EdgeConstraint> edges;    ///< hull edges
  std::vector<SpokeConstraint> spokes;  ///< one per control point, in point order
  std::vector<BendConstraint> bends;    ///< one per hull edge shared by two triangles and folded enough
  std::array<uint32_t, 2> edge_half_end{};
  std::array<uint32_t, 2> bend_half_end{};
  /// The spokes (columns) in sweep order: those of the points of one half, column_order[0 ..
  /// column_half_end), then the other's.
  std::vector<uint32_t> column_order;
  uint32_t column_half_end = 0;
  /// The control surface's triangles, outward winding: an obstacle poking through one between its
  /// corners pushes them in (face contacts).
  std::vector<std::array<uint32_t, 3>> triangles;
  /// triangleNeighbours(triangles): the triangle across each edge, for the pseudo-normals of another
  /// body's contacts with this one (deform/body_group.hpp).
  std::vector<uint32_t> triangle_across;
  std::vector<double> edge_rest_m;   ///< original rest lengths L0, one per edge [m]
  std::vector<double> spoke_rest_m;  ///< original rest lengths L0, one per spoke [m]
  /// Where each spoke is anchored on the core, relative to core_m (it moves with the core) [m]: the foot
  /// of the core on the line through the point along its area normal, so the column runs along the
  /// skin's normal (see createBodySettings); core_m itself where that foot is not inside.
  std::vector<Eigen::Vector3d> spoke_anchor_m;
  /// Outward unit normal of each spoke's patch of skin, a / |a| (zero where the patch has no area): the
  /// direction a crush column resists by its full area (columnYield_m).
  std::vector<Eigen::Vector3d> spoke_normal;
  std::vector<double> bend_rest_m;       ///< original rest lengths L0, one per bend [m]
  std::vector<YieldLimits> edge_yield;   ///< elastic range of each edge (from its material and strip) [m]
  std::vector<YieldLimits> spoke_yield;  ///< elastic range of each spoke (crush column) [m]
  std::vector<YieldLimits> bend_yield;   ///< elastic range of each bend [m]
  /// Skin area each control point stands for, as seen along its normal: the length of the sum of a third
  /// of its triangles' area vectors [m^2].
  std::vector<double> tributary_area_m2;

  bool anchored_columns = false;         ///< BodyDescription::anchored_columns
  std::vector<Material> materials;       ///< [0] = the default, then one per region
  std::vector<PlasticLaw> plastic_laws;  ///< the plasticity part of each material, same indexing

  std::size_t pointCount() const { return rest_positions_m.size(); }  ///< control points
  /// Edges, spokes and bends together.
  std::size_t constraintCount() const { return edges.size() + spokes.size() + bends.size(); }
};

/// Builds the constraint arrays (edges, spokes, bends), inverse masses, and each constraint's compliance
/// and yield limits from its material and the geometry it stands for (material.hpp).
/// A point mass that is not positive (a control point with no tetrahedron volume) gets 1e-3 of the mean
/// point mass, so no inverse mass is infinite. Throws InputError naming the field for a mismatched mass
/// split, a bad material, a region or override index out of range, or a deviation that is not finite
/// and positive.
BodySettings createBodySettings(const ControlMesh& mesh, const MassSplit& masses,
                                const BodyDescription& description);

}  // namespace deform
