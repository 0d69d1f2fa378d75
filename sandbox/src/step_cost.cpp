#include "step_cost.hpp"

#include "elapsed.hpp"

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

deform::SolverParams paramsOf(const StepCostOptions& options, uint32_t threads) {
  deform::SolverParams params;
  params.substeps = options.substeps;
  params.iterations = options.iterations;
  params.yield_limited = options.yield_limited;
  params.threads = threads;
  params.wide_sweep = options.wide_sweep;
  params.sleep_delay_s = -1;  // measure work, not sleep
  return params;
}

// A wall across the front, 5 cm into the body: solid where x > front - 0.05.
deform::StepInputs wallInputs(const deform::BodySettings& settings) {
  double front_m = -1e300;
  for (const auto& p : settings.rest_positions_m) front_m = std::max(front_m, p.x());
  deform::StepInputs inputs;
  inputs.contacts.push_back(deform::HalfSpaceShape{{-1, 0, 0}, -(front_m - 0.05)});
  inputs.chassis.gravity_mps2 = {0, 0, -9.81};
  return inputs;
}

double wallMicroseconds(deform::DeformableBody& body, const deform::StepInputs& inputs, double dt_s) {
  const auto start = std::chrono::steady_clock::now();
  body.step(inputs, dt_s);
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

StepCost measureStepCost(const std::shared_ptr<const deform::BodySettings>& settings,
                         const StepCostOptions& options) {
  deform::DeformableBody body(settings, paramsOf(options, options.threads));
  const deform::StepInputs inputs = wallInputs(*settings);

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

ThreadSpeedup measureThreadSpeedup(const std::shared_ptr<const deform::BodySettings>& settings,
                                   const StepCostOptions& options, std::size_t block) {
  block = std::max<std::size_t>(block, 1);
  // One body whose thread count changes between blocks: two bodies would share the cores' caches and
  // both run slower than either alone.
  deform::DeformableBody body(settings, paramsOf(options, 1));
  const deform::StepInputs inputs = wallInputs(*settings);
  for (std::size_t k = 0; k < options.warmup; ++k) body.step(inputs, options.dt_s);
  // The block's median step: its first steps, after the change of threads, are outliers it leaves out.
  auto runBlock = [&](uint32_t threads, std::vector<double>& all_us) {
    body.setParams(paramsOf(options, threads));
    std::vector<double> us(block);
    for (double& t : us) t = wallMicroseconds(body, inputs, options.dt_s);
    all_us.insert(all_us.end(), us.begin(), us.end());
    return median(us);
  };
  const std::size_t pairs = std::max<std::size_t>(1, (options.steps + block - 1) / block);
  std::vector<double> one_us, many_us, ratios;
  for (std::size_t k = 0; k < pairs; ++k) {
    double one_block_us = 0, many_block_us = 0;
    if (k % 2 == 0) {
      one_block_us = runBlock(1, one_us);
      many_block_us = runBlock(options.threads, many_us);
    } else {
      many_block_us = runBlock(options.threads, many_us);
      one_block_us = runBlock(1, one_us);
    }
    ratios.push_back(one_block_us / many_block_us);
  }
  ThreadSpeedup out;
  out.one_thread_wall_us = median(one_us);
  out.many_threads_wall_us = median(many_us);
  out.speedup = median(ratios);
  out.speedup_low = quantile(ratios, 0.25);
  out.speedup_high = quantile(ratios, 0.75);
  out.pairs = ratios.size();
  out.mixed_hash = deform::hashState(body.state());
  // The same steps on one thread throughout (not timed).
  deform::DeformableBody reference(settings, paramsOf(options, 1));
  for (std::size_t k = 0; k < options.warmup + 2 * pairs * block; ++k) reference.step(inputs, options.dt_s);
  out.one_thread_hash = deform::hashState(reference.state());
  return out;
}

}  // namespace sandbox
