#include "stress/random_checks.hpp"

#include "stress/stress_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace sandbox {
namespace {

using stress_support::bounded;
using stress_support::format;

double kinetic_J(const vehicle::Car& car) {
  return 0.5 * car.mass_kg() * car.velocity_mps().squaredNorm();
}

// Every figure of the car's metrics finite.
bool metricsFinite(const vehicle::CrashMetrics& m) {
  const vehicle::EnergyTerms& e = m.energy;
  for (const double value :
       {m.impact_speed_mps, m.rebound_speed_mps, m.residual_crush_m, m.max_residual_crush_m,
        m.max_deviation_m, m.max_penetration_m, e.kinetic_initial_J, e.plastic_work_J, e.damping_loss_J,
        e.contact_loss_J, e.elastic_energy_J, e.contact_work_J, e.inertial_work_J, e.obstacle_work_J,
        e.kinetic_final_J, e.crush_work_J, e.other_work_J, e.balance_error_J})
    if (!std::isfinite(value)) return false;
  return true;
}

}  // namespace

std::vector<CarTrace> playTraced(scenes::SceneRun& run) {
  const vehicle::Simulation& simulation = run.simulation();
  std::vector<CarTrace> traces(run.carCount());
  auto trace = [&](bool start) {
    for (std::size_t i = 0; i < run.carCount(); ++i) {
      const vehicle::Car& car = simulation.world().car(run.carId(i));
      const double height_m = car.bodyPose().position_m.z();
      CarTrace& t = traces[i];
      if (start) t.start_height_m = height_m;
      if (std::isfinite(height_m)) t.max_rise_m = std::max(t.max_rise_m, height_m - t.start_height_m);
      if (!simulation.metrics(run.carId(i)).impacted)
        t.kinetic_before_impact_J = std::max(t.kinetic_before_impact_J, kinetic_J(car));
    }
  };
  trace(true);
  while (!run.finished()) {
    run.step();
    trace(false);
  }
  return traces;
}

RunVerdict checkRandomRun(const scenes::SceneRun& run, const std::vector<CarTrace>& traces,
                          RandomRunFigures& figures) {
  RunVerdict verdict;
  const vehicle::Simulation& simulation = run.simulation();
  const double gravity_mps2 = run.scene().gravity_mps2;
  // Every car's energy before it hit anything, or the energy through the whole run (the watch's: the
  // start's, the engines' work and the potential energy given up) where that is more: the most any car can
  // be raised with (a car at rest raised by its engine's work alone).
  double brought_J = 0;
  for (std::size_t i = 0; i < run.carCount(); ++i)
    brought_J += std::max(traces[i].kinetic_before_impact_J,
                          simulation.metrics(run.carId(i)).energy.kinetic_initial_J);
  brought_J = std::max(brought_J, simulation.energyWatch().through_J);
  figures = {};
  figures.car_balance_percent = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < run.carCount(); ++i) {
    const vehicle::CarId id = run.carId(i);
    const vehicle::CrashMetrics m = simulation.metrics(id);
    const vehicle::Car& car = simulation.world().car(id);
    const std::string name = "car" + std::to_string(i) + ": ";
    if (m.diverged) verdict.fail(name + "diverged: " + m.diverged_what);
    bool finite = metricsFinite(m) && bounded(car.bodyPose().position_m) && bounded(car.velocity_mps());
    for (const Eigen::Vector3d& p : simulation.controlPoints(id)) finite = finite && bounded(p);
    if (!finite) verdict.fail(name + "not finite or beyond 1e10");
    if (m.tunnelled) verdict.fail(name + "tunnelled");
    // No launch: the car alone raised by every car's energy (and a margin) rises no higher than this.
    const double bound_m = (1 + kLaunchMargin) * brought_J / (car.mass_kg() * gravity_mps2) + kLaunchSlack_m;
    figures.max_rise_m = std::max(figures.max_rise_m, traces[i].max_rise_m);
    if (!(traces[i].max_rise_m <= bound_m))
      verdict.fail(name +
                   format("rose %.2f m, above the ballistic bound %.2f m", traces[i].max_rise_m, bound_m));
    if (!m.impacted) continue;
    ++figures.impacted;
    // Each car's own balance (docs/CRASH_CALIBRATION.md, "Energy account"), for the table: what the car
    // had and was given less everything measured that it lost or holds. Between cars it books the other's
    // push through the obstacles' work, which is not exact, so the verdict is the whole run's (below).
    const vehicle::EnergyTerms& e = m.energy;
    const double impact_J = e.kinetic_initial_J + std::max(0.0, e.obstacle_work_J);
    const double created_percent = impact_J > 0 ? -100 * e.balance_error_J / impact_J : 0.0;
    figures.car_balance_percent = std::max(figures.car_balance_percent, created_percent);
  }
  // Energy not created: the energy watch's account of every car and free obstacle together
  // (vehicle::Simulation::energyWatch), which marks the run diverged past its tolerance; checked here
  // again in case a run diverged on something else first.
  const vehicle::Simulation::EnergyWatchReport watch = simulation.energyWatch();
  figures.created_percent = 100 * watch.largest_created_share;
  if (watch.largest_created_share > vehicle::kEnergyWatchTolerance)
    verdict.fail(format("created %.3g J, %.3g %% of the %.3g J through the run", watch.largest_created_J,
                        figures.created_percent, watch.through_J));
  if (figures.impacted == 0) figures.car_balance_percent = 0;
  return verdict;
}

}  // namespace sandbox
