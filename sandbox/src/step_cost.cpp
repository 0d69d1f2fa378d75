#include "step_cost.hpp"

#include <deform/deformable_body.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

namespace sandbox {
namespace {

// This thread's CPU time [us]: other processes on a shared machine preempt it (wall time is kept too).
double cpuMicroseconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

StepCost measureStepCost(const std::shared_ptr<const deform::BodySettings>& settings,
                         const StepCostOptions& options) {
  deform::SolverParams params;
  params.substeps = options.substeps;
  params.iterations = options.iterations;
  params.yield_limited = options.yield_limited;
  params.threads = options.threads;
  params.wide_sweep = options.wide_sweep;
  params.sleep_delay_s = -1;  // measure work, not sleep
  deform::DeformableBody body(settings, params);

  // A wall across the front, 5 cm into the body: solid where x > front - 0.05.
  double front_m = -1e300;
  for (const auto& p : settings->rest_positions_m) front_m = std::max(front_m, p.x());
  deform::StepInputs inputs;
  inputs.contacts.push_back(deform::HalfSpaceShape{{-1, 0, 0}, -(front_m - 0.05)});
  inputs.chassis.gravity_mps2 = {0, 0, -9.81};

  StepCost cost;
  for (std::size_t k = 0; k < options.warmup; ++k) body.step(inputs, options.dt_s);
  const std::size_t steps = std::max<std::size_t>(options.steps, 1);
  std::vector<double> us(steps), wall_us(steps);
  for (std::size_t k = 0; k < steps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = cpuMicroseconds();
    const deform::StepReport report = body.step(inputs, options.dt_s);
    us[k] = cpuMicroseconds() - cpu_start;
    wall_us[k] = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    cost.contact_points = std::max(cost.contact_points, report.contact_points / options.substeps);
  }
  cost.us_per_step = median(us);
  cost.wall_us_per_step = median(wall_us);
  cost.ns_per_constraint_iteration =
      (options.threads > 1 ? cost.wall_us_per_step : cost.us_per_step) * 1e3 /
      (static_cast<double>(settings->constraintCount()) * options.substeps * options.iterations);
  cost.max_deviation_m = deform::maxDeviation(*settings, body.state());
  for (std::size_t i = 0; i < settings->pointCount(); ++i)
    cost.points_at_cap += (body.state().positions_m[i] - settings->rest_positions_m[i]).norm() >=
                          settings->max_deviation_m[i] - 1e-3;
  cost.state_hash = deform::hashState(body.state());
  return cost;
}

}  // namespace sandbox
