#pragma once
// The cost of one step of a deformable body under a contact: a wall pressed 5 cm into the front of the
// body for every measured step (shared by `bench step`, `bench grid` and the full-resolution baseline).
#include <deform/body_settings.hpp>

#include <cstdint>
#include <memory>

namespace sandbox {

struct StepCost {
  double us_per_step = 0;       ///< median thread CPU time of one step [us]
  double wall_us_per_step = 0;  ///< median wall time [us]
  double ns_per_constraint_iteration = 0;
  uint32_t contact_points = 0;  ///< points against the wall in a substep
  double max_deviation_m = 0;   ///< at the end [m]
  /// Points within 1 mm of their visual-constraint cap at the end: a body that sags onto its caps is
  /// measured in that state, which is not what a crash's body does.
  uint32_t points_at_cap = 0;
  uint64_t state_hash = 0;  ///< deform::hashState of the body at the end
};

struct StepCostOptions {
  uint32_t substeps = 4;
  uint32_t iterations = 1;
  std::size_t warmup = 20;  ///< steps before measuring (the wall has crushed the front by then)
  std::size_t steps = 200;  ///< measured steps (the median is reported)
  double dt_s = 1.0 / 60;
  bool yield_limited = false;  ///< deform::SolverParams::yield_limited
  uint32_t threads = 1;        ///< deform::SolverParams::threads
  bool wide_sweep = true;      ///< deform::SolverParams::wide_sweep
};

/// Steps a body of `settings` (sleep off) under the wall and times it. ns_per_constraint_iteration is of
/// the thread CPU time on one thread and of the wall time on more (the CPU time of the calling thread
/// leaves out the other's).
StepCost measureStepCost(const std::shared_ptr<const deform::BodySettings>& settings,
                         const StepCostOptions& options);

/// One thread against `threads` on the same body, measured in one process: the body under the wall steps
/// in blocks of `block` steps on one thread and on `threads` in turn (which comes first alternates), so
/// that a neighbour's load on a shared machine falls on both alike. Each pair of blocks gives one ratio
/// of their median wall times per step; the speed-up is the median of the ratios.
struct ThreadSpeedup {
  double one_thread_wall_us = 0;    ///< median over all one-thread steps [us]
  double many_threads_wall_us = 0;  ///< the same on `threads` threads [us]
  double speedup = 0;               ///< median of the pairs' ratios (one thread / many)
  double speedup_low = 0;           ///< their lower quartile
  double speedup_high = 0;          ///< their upper quartile
  std::size_t pairs = 0;            ///< pairs of blocks measured
  /// deform::hashState after the mixed steps, and after as many steps on one thread throughout: equal
  /// when the result does not depend on the thread count.
  uint64_t mixed_hash = 0;
  uint64_t one_thread_hash = 0;
};

ThreadSpeedup measureThreadSpeedup(const std::shared_ptr<const deform::BodySettings>& settings,
                                   const StepCostOptions& options, std::size_t block = 20);

}  // namespace sandbox
