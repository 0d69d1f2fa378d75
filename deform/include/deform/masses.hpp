#pragma once
// Mass distribution over the control points: Kenwright 2015, Figure "Non-Linear Control Element
// Coupling": the hull is cut into a tetrahedral fan from the centre of mass to every hull triangle; each
// tetrahedron's share of the vehicle mass (by volume) goes one quarter to each of its corners.
#include <deform/control_mesh.hpp>

#include <vector>

namespace deform {

/// A body's mass shared between its control points and the rigid core.
struct MassSplit {
  std::vector<double> point_mass_kg;  ///< one per control point [kg]
  double core_mass_kg = 0;            ///< the centre's share: the rigid core (chassis) [kg]
  double total_kg() const;            ///< points plus core [kg]
};

/// Splits `vehicle_mass_kg` over the control points and the core by the tetrahedral fan (Kenwright 2015).
/// Throws InputError for a mass that is not finite and positive.
MassSplit distributeMass(const ControlMesh& mesh, double vehicle_mass_kg);

}  // namespace deform
