#pragma once
// Stability at the extremes (DESIGN.md section 7): scene runs pushed to the ends of every range, each
// checking what must hold there (finite state, nothing beyond 1e10, no tunnelling, deviation within the
// visual constraint, energy not created, the same hash twice). `sandbox stress` prints the long version
// as a table; the `[extreme]` tests run the quick one and fail on any case that does not hold.
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace sandbox {

/// One case: what it ran, what it checks, and whether that held.
struct StressCase {
  StressCase() = default;
  StressCase(std::string group_name, std::string case_name, std::string what_must_hold)
      : group(std::move(group_name)), name(std::move(case_name)), checks(std::move(what_must_hold)) {}

  std::string group;   ///< the range it belongs to ("impact_speed", ...)
  std::string name;    ///< the value tried ("500 km/h")
  std::string checks;  ///< what must hold, in words
  bool passed = false;
  std::string detail;  ///< the measured figures, and what failed first when it did
  double seconds = 0;  ///< wall time of the case [s]
};

/// Names of the groups, in the order the table lists them.
std::vector<std::string> stressGroups();

/// Runs one group. `quick` takes the ends of each range only (for CI); otherwise the whole range.
/// Throws std::invalid_argument for an unknown group.
std::vector<StressCase> runStressGroup(const std::string& group, bool quick);

/// Runs every group, calling `on_case` after each case (for progress).
std::vector<StressCase> runStressSuite(bool quick,
                                       const std::function<void(const StressCase&)>& on_case = {});

}  // namespace sandbox
