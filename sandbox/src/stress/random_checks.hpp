#pragma once
// The invariants a random crash scene is held to (`sandbox stress --random`, DESIGN.md section 7), per car:
// energy not created, no launch past the ballistic bound, nothing diverged or not finite, no tunnelling.
// The same hash on a second run is the campaign's (random_campaign.cpp).
#include <scenes/scene_run.hpp>

#include <vector>

#include "stress/stress_checks.hpp"

namespace sandbox {

/// The launch bound: every car's energy with this margin, as height of the car alone, plus a slack for
/// the suspension and a car tipped on its side [-], [m].
inline constexpr double kLaunchMargin = 0.10;
inline constexpr double kLaunchSlack_m = 0.1;

/// What a run traced of one car, step by step.
struct CarTrace {
  double start_height_m = 0;  ///< its centre of mass at the start [m]
  double max_rise_m = 0;      ///< the highest its centre of mass rose above that [m]
  /// Its largest kinetic energy (chassis translation) before its first impact, the start's included:
  /// what it brought, drive included [J].
  double kinetic_before_impact_J = 0;
};

/// Plays `run` to its end one step at a time, tracing every car.
std::vector<CarTrace> playTraced(scenes::SceneRun& run);

/// The figures of a random run for the table.
struct RandomRunFigures {
  /// The most energy the run created (the energy watch: every car and free obstacle), in % of the energy
  /// through it; 0 when it created none.
  double created_percent = 0;
  /// The largest energy an impacted car's own balance leaves unexplained on the side of creation, in % of
  /// its impact energy (negative: a loss); 0 when no car impacted. Information, not a verdict.
  double car_balance_percent = 0;
  double max_rise_m = 0;     ///< the largest rise of any car [m]
  std::size_t impacted = 0;  ///< cars that hit something
};

/// Checks every car of the finished `run` (traced by playTraced) and fills `figures`.
RunVerdict checkRandomRun(const scenes::SceneRun& run, const std::vector<CarTrace>& traces,
                          RandomRunFigures& figures);

}  // namespace sandbox
