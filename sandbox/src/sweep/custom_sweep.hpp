#pragma once
// The custom sweep: scenes crossed with a grid of `--vary key=v1,v2,...` scene keys, each combination
// played to its end and its crash measured (sweep_case.hpp, measure "crash"). Its merge writes sweep.csv
// and sweep.md: one row per case, the varied keys' values first.
#include "sweep/sweep_plan.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sandbox {

struct CustomSweepOptions {
  std::vector<std::string> scenes;  ///< one or more
  std::vector<std::string> vary;    ///< "key=v1,v2,...": every combination (the last key varies fastest)
  std::vector<std::string> sets;    ///< overrides for every run, before the varied keys
};

/// The plan: every scene, every combination. Each case is loaded once here, so a bad key or value is
/// refused (deform::InputError naming --vary or the scene key) before anything runs.
SweepPlan planCustom(const CustomSweepOptions& options);

/// sweep.csv and sweep.md into `dir` from a custom plan and each case's measure (the plan's order).
void writeCustomReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                       const std::string& dir);

}  // namespace sandbox
