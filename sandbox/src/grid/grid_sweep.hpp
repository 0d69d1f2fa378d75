#pragma once
// The benchmark grid as a sweep (sweep/sweep_plan.hpp, kind "grid"): one case per render-mesh resolution
// (its rows: the skin at every control-point count, the baselines) and one per Bullet wall-crash speed, and
// the report `sandbox bench grid` writes: grid.csv, bullet_crash.csv and grid.png. The cases build the
// built-in sedan in code: they name no scene file. Nearly every figure is a timing; a resolution measured
// in its own process measures the step's cost again rather than reusing another resolution's.
#include "sweep/sweep_plan.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sandbox {

/// The plan of `sandbox bench grid [--quick] [--threads T]`.
SweepPlan planGrid(bool quick, unsigned threads);

/// One case (the "grid" measure): {"rows": [...]} for a resolution, {"crash": {...}} for a crash speed.
nlohmann::json measureGridCase(const SweepCase& sweep_case);

/// grid.csv, bullet_crash.csv and the plot into `dir`, from a grid plan and each case's measure; prints
/// each row and crash.
void writeGridReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                     const std::string& dir);

}  // namespace sandbox
