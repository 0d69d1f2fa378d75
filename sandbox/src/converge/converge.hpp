#pragma once
// The convergence study (DESIGN.md section 6: the reference is only a reference because the model converges
// there): the 56 km/h wall crash and the 32 km/h side pole at N = 60 .. 2000 control points, as a sweep plan
// (sweep/sweep_plan.hpp, kind "converge", each case measured by the "crash" measure) and its report:
// converge.csv, converge.md and a plot of residual crush against N.
#include "sweep/sweep_plan.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sandbox {

struct ConvergeOptions {
  bool quick = false;             ///< 60 and 250 points only
  std::vector<std::string> sets;  ///< scene overrides for every run (the level of detail is set last)
};

/// The plan: each scene at each level. Loads each scene with the overrides first, so a bad key is refused
/// (deform::InputError naming it) before anything runs.
SweepPlan planConverge(const ConvergeOptions& options);

/// converge.csv, converge.md, the per-scene data and converge.png into `dir`, from a converge plan and each
/// case's crash measure (the plan's order). Prints one line per case.
void writeConvergeReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                         const std::string& dir);

}  // namespace sandbox
