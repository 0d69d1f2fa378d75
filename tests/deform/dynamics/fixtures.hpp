#pragma once
// Test bodies for the deformation dynamics: an icosahedron (every vertex alike, so pressing all of them
// equally is a uniform compression with an exact answer) and hulls of points on a sphere.
#include <deform/body_settings.hpp>
#include <deform/body_state.hpp>
#include <deform/deformable_body.hpp>

#include <memory>
#include <vector>

namespace dynamics_test {

/// Regular icosahedron of circumradius `radius_m` centred on the origin (12 points, 30 edges).
deform::ControlMesh icosahedron(double radius_m = 1.0);

/// Convex hull of `count` points on a sphere (Fibonacci lattice); a tetrahedron for count == 4.
deform::ControlMesh sphereHull(std::size_t count, double radius_m = 1.0);

/// The built-in sedan (its 2,000-vertex body) reduced to `points` control points.
deform::ControlMesh sedanControlMesh(std::size_t points);

/// Body settings from a control mesh and a total mass, fan-distributed (distributeMass).
std::shared_ptr<const deform::BodySettings> makeSettings(const deform::ControlMesh& mesh, double mass_kg,
                                                         const deform::BodyDescription& description);

/// A material that never yields, with the given compliance for every kind [m/N].
/// Constraint constants set directly, for tests of the solver's math on bodies that are not cars: every
/// edge, spoke and bend gets these compliances and yields at yield_strain x its original length.
struct UniformMaterial {
  double edge_compliance_m_per_N = 1e-6;
  double spoke_compliance_m_per_N = 1e-5;
  double bend_compliance_m_per_N = 1e-5;
  double yield_strain = 0.02;  ///< [1]; 1e9 = elastic
};

/// makeSettings, then the uniform constants over the physical material's.
std::shared_ptr<const deform::BodySettings> makeSettings(const deform::ControlMesh& mesh, double mass_kg,
                                                         const deform::BodyDescription& description,
                                                         const UniformMaterial& uniform);

/// Elastic (never yields), every compliance `compliance_m_per_N`.
UniformMaterial elasticMaterial(double compliance_m_per_N);

/// Half-spaces pressing every vertex of a body centred on the origin radially inwards, each to the
/// radius `reach_m` (one plane per vertex, normal along it).
std::vector<deform::ContactShape> radialPlates(const deform::BodySettings& settings, double reach_m);

/// Largest |value| over positions, velocities and rest lengths; infinite when any is NaN or infinite.
double largestMagnitude(const deform::BodyState& state);

/// Largest |x - x0| - d_max over the points [m] (<= 0 when the visual constraint holds).
double worstDeviationExcess(const deform::BodySettings& settings, const deform::BodyState& state);

/// Mean distance of the control points from the core [m].
double meanRadius(const deform::BodySettings& settings, const deform::BodyState& state);

}  // namespace dynamics_test
