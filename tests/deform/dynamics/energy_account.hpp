#pragma once
// The body's energy account, step by step, in the step's inertial frame (the chassis's motion when the
// step begins): the obstacle's work J . V goes into plastic work, viscous and contact losses, and the
// change of the energy the body holds (points' and core's kinetic energy, the constraints' elastic energy
// at the forces the solve carried, 1/2 alpha F^2, as the vehicle's account takes it: where a stiff solve
// has not converged, 1/2 C^2 / alpha of the geometry is mostly error the solve has yet to correct). Each term
// is measured on its own; what is left is the solver's own numerical loss (XPBD is implicit Euler in each
// substep: a constraint loaded by dx in a substep takes k dx^2 / 2 more than it stores). It may be lost,
// never created.
#include <deform/body_settings.hpp>
#include <deform/deformable_body.hpp>
#include <deform/solver_params.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

namespace dynamics_test {

struct EnergyAccount {
  double obstacle_work_J = 0, plastic_J = 0, damping_J = 0, contact_loss_J = 0, held_change_J = 0;
  double worst_step_creation_J = 0;  ///< the largest energy one step created (a negative residual) [J]
  /// Momentum: the largest |change of the points' and core's momentum - the obstacle's impulse| of a step
  /// (a free core only), and the sum of |impulse| over the steps [N s].
  double worst_momentum_error_Ns = 0, impulse_Ns = 0;
  /// What no term explains: > 0 lost by the solver, < 0 created [J].
  double unexplained_J() const {
    return obstacle_work_J - plastic_J - damping_J - contact_loss_J - held_change_J;
  }
};

/// The body's energy relative to `frame` [m/s]: points' and core's kinetic, constraints' elastic.
double heldEnergy_J(const deform::DeformableBody& body, const Eigen::Vector3d& frame, double core_mass_kg,
                    const Eigen::Vector3d& core_velocity);

/// The points' and the core's momentum relative to `frame` [N s].
Eigen::Vector3d momentum_Ns(const deform::DeformableBody& body, const Eigen::Vector3d& frame,
                            double core_mass_kg, const Eigen::Vector3d& core_velocity);

/// How an obstacle is driven into a body: closing along `direction` at `speed_mps`, less what the core
/// has been slowed by, for `steps` steps of `dt_s`.
struct ObstacleDrive {
  deform::SolverParams params;
  double dt_s = 1.0 / 500;
  int steps = 150;
  double speed_mps = 4.0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  double core_mass_kg = 1125.0;  ///< infinite: a kinematic core
  double friction = 0.3;
};

/// Drives the obstacle `place(travel_m)` (where it is when the step ends, `travel_m` how far it has come
/// relative to the core) into a body of `settings`; the account summed over the steps. `each(body)` is
/// called after every step.
template <typename Place, typename Each>
EnergyAccount driveObstacle(const std::shared_ptr<const deform::BodySettings>& settings,
                            const ObstacleDrive& drive, Place place, Each each) {
  using deform::StepInputs;
  deform::DeformableBody body(settings, drive.params);
  const bool free_core = std::isfinite(drive.core_mass_kg);
  const double core_mass_kg = free_core ? drive.core_mass_kg : 0.0;
  EnergyAccount total;
  double closing_mps = drive.speed_mps, travel_m = 0;
  for (int k = 0; k < drive.steps; ++k) {
    StepInputs inputs;
    inputs.contacts = {place(travel_m + closing_mps * drive.dt_s)};
    inputs.surface_contact = {1};
    const Eigen::Vector3d obstacle_mps = -closing_mps * drive.direction;
    inputs.contact_velocity_mps = {obstacle_mps};
    inputs.core_mass_kg = drive.core_mass_kg;
    inputs.contact_friction = drive.friction;
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    const double before_J = heldEnergy_J(body, zero, core_mass_kg, zero);
    const Eigen::Vector3d before_Ns = momentum_Ns(body, zero, core_mass_kg, zero);
    const deform::StepReport r = body.step(inputs, drive.dt_s);
    // The state is re-centred on the core: in the step's frame the points move at v + the core's velocity.
    const double after_J = heldEnergy_J(body, r.core_velocity_mps, core_mass_kg, r.core_velocity_mps);
    if (free_core) {
      const Eigen::Vector3d after_Ns =
          momentum_Ns(body, r.core_velocity_mps, core_mass_kg, r.core_velocity_mps);
      const double error_Ns = (after_Ns - before_Ns - r.contact_impulse_Ns).norm();
      total.worst_momentum_error_Ns = std::max(total.worst_momentum_error_Ns, error_Ns);
    }
    total.impulse_Ns += r.contact_impulse_Ns.norm();
    EnergyAccount step;
    step.obstacle_work_J = r.contact_impulse_Ns.dot(obstacle_mps);
    step.plastic_J = r.plastic_work_J;
    step.damping_J = r.damping_loss_J;
    step.contact_loss_J = r.contact_loss_J;
    step.held_change_J = after_J - before_J;
    total.obstacle_work_J += step.obstacle_work_J;
    total.plastic_J += step.plastic_J;
    total.damping_J += step.damping_J;
    total.contact_loss_J += step.contact_loss_J;
    total.held_change_J += step.held_change_J;  // a sum over frames: only the residual is meaningful
    total.worst_step_creation_J = std::max(total.worst_step_creation_J, -step.unexplained_J());
    // The next step's frame is the core's: the obstacle comes on at the speed the core has left, and is
    // nearer by how far the core moved within this step.
    travel_m += closing_mps * drive.dt_s + r.core_displacement_m.dot(drive.direction);
    closing_mps += r.core_velocity_mps.dot(drive.direction);
    each(body);
  }
  return total;
}

template <typename Place>
EnergyAccount driveObstacle(const std::shared_ptr<const deform::BodySettings>& settings,
                            const ObstacleDrive& drive, Place place) {
  return driveObstacle(settings, drive, place, [](const deform::DeformableBody&) {});
}

}  // namespace dynamics_test
