#include "stress/stress_checks.hpp"

#include "stress/stress_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sandbox {
namespace {

using stress_support::bounded;

}  // namespace

RunVerdict checkRun(const scenes::SceneRun& run) {
  RunVerdict verdict;
  const vehicle::Simulation& simulation = run.simulation();
  for (std::size_t i = 0; i < run.carCount(); ++i) {
    const vehicle::CarId id = run.carId(i);
    const vehicle::CrashMetrics m = simulation.metrics(id);
    const std::string car = run.carCount() > 1 ? "car " + std::to_string(i) + ": " : "";
    if (m.diverged) verdict.fail(car + "diverged");
    for (const Eigen::Vector3d& p : simulation.controlPoints(id)) {
      if (!bounded(p)) {
        verdict.fail(car + "a control point is not finite or beyond 1e10");
        break;
      }
    }
    if (!bounded(simulation.world().car(id).vehiclePose().position_m))
      verdict.fail(car + "chassis not finite");
    if (m.tunnelled) verdict.fail(car + "tunnelled");
    const double cap_m = simulation.deformationSettings(id).max_deviation_m;
    if (!(m.max_deviation_m <= cap_m * (1 + 1e-9)))
      verdict.fail(car + "deviation beyond the visual constraint");
    const vehicle::EnergyTerms& e = m.energy;
    if (simulation.deformationSettings(id).coupling == vehicle::Coupling::Crush && m.impacted) {
      // Within 5 % of the energy that went through the body (the balance the energy account is held to,
      // docs/CRASH_CALIBRATION.md): the first impact's, or in a run of many impacts (each fed by the
      // drive) what the body took in all, plastic work and losses. The 1 kg car sits near 2-3 %: the
      // sweep's order alone moved it between 1.7 and 3.1 % (-2.1 to -3.8 J of 121 J, docs/STABILITY.md).
      const double through_J = std::max(
          e.kinetic_initial_J, e.plastic_work_J + e.damping_loss_J + std::max(0.0, e.contact_loss_J));
      const double tolerance_J = 0.05 * through_J + 1.0;
      // Energy not created: every measured term together (plastic work, viscous and contact losses,
      // elastic energy, ODE's work) explains no more than the whole car lost.
      if (e.balance_error_J < -tolerance_J) {
        char amount[96];
        std::snprintf(amount, sizeof amount, " (by %.3g J, %.2g %% of the %.3g J that went through)",
                      -e.balance_error_J, 100 * -e.balance_error_J / through_J, through_J);
        verdict.fail(car + "the body took more energy than the car lost" + amount);
      }
      // Nor did the body's plastic work and viscous loss exceed the work done on it in the chassis's
      // frame: the obstacles' and the inertial forces' (a chassis stopped rigidly throws its shell forward).
      if (e.plastic_work_J + e.damping_loss_J > e.contact_work_J + e.inertial_work_J + tolerance_J)
        verdict.fail(car + "the body holds more energy than what hit it put in");
    }
    char figures[384];
    std::snprintf(figures, sizeof figures,
                  "%simpact %.1f km/h, crush %.3f m (largest %.3f), deviation %.3f of %.2f m, plastic %.3g J "
                  "of %.3g J, unexplained %.3g J, restitution %.2f, penetration %.1f mm",
                  car.c_str(), 3.6 * m.impact_speed_mps, m.residual_crush_m, m.max_residual_crush_m,
                  m.max_deviation_m, cap_m, e.plastic_work_J, e.kinetic_initial_J, e.balance_error_J,
                  m.restitution, 1e3 * m.max_penetration_m);
    verdict.figures += (verdict.figures.empty() ? "" : "; ") + std::string(figures);
  }
  return verdict;
}

}  // namespace sandbox
