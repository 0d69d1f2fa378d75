#pragma once
// Mass properties of a closed solid of uniform density from its outward triangulated surface: the
// signed-tetrahedron decomposition (each triangle with the origin), whose second moment is
// int x x^T dV = V/20 (sum_i v_i v_i^T + s s^T), s = sum_i v_i over the tetrahedron's corners
// (Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor", J. Math. Stat. 2004; Eberly,
// "Polyhedral Mass Properties (Revisited)", 2002). The same fan as deform's mass split.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace vehicle {

struct SolidProperties {
  double volume_m3 = 0;                                      ///< enclosed volume [m^3]
  Eigen::Vector3d centroid_m{0, 0, 0};                       ///< centre of volume [m]
  Eigen::Matrix3d inertia_per_kg = Eigen::Matrix3d::Zero();  ///< inertia about the centroid for 1 kg [m^2]
};

/// Properties of the solid bounded by `triangles` over `points` (closed, outward winding). Throws
/// deform::InputError naming `source` for a surface enclosing no volume.
SolidProperties solidProperties(const std::vector<Eigen::Vector3d>& points,
                                const std::vector<std::array<uint32_t, 3>>& triangles,
                                const char* source = "hull");

/// Inertia about a point displaced by `offset_m` from the centre of mass, for mass `mass_kg`, given the
/// inertia about the centre of mass (parallel axis theorem) [kg m^2].
Eigen::Matrix3d shiftedInertia(const Eigen::Matrix3d& inertia_com_kg_m2, double mass_kg,
                               const Eigen::Vector3d& offset_m);

}  // namespace vehicle
