#include "energy_account.hpp"

namespace dynamics_test {

double heldEnergy_J(const deform::DeformableBody& body, const Eigen::Vector3d& frame, double core_mass_kg,
                    const Eigen::Vector3d& core_velocity) {
  const deform::BodySettings& s = body.settings();
  const deform::BodyState& state = body.state();
  double e = body.carriedElasticEnergy_J() + 0.5 * core_mass_kg * core_velocity.squaredNorm();
  for (std::size_t i = 0; i < s.pointCount(); ++i)
    e += 0.5 * s.mass_kg[i] * (state.velocities_mps[i] + frame).squaredNorm();
  return e;
}

Eigen::Vector3d momentum_Ns(const deform::DeformableBody& body, const Eigen::Vector3d& frame,
                            double core_mass_kg, const Eigen::Vector3d& core_velocity) {
  const deform::BodySettings& s = body.settings();
  Eigen::Vector3d p = core_mass_kg * core_velocity;
  for (std::size_t i = 0; i < s.pointCount(); ++i)
    p += s.mass_kg[i] * (body.state().velocities_mps[i] + frame);
  return p;
}

}  // namespace dynamics_test
