#pragma once
// The stress suite as a sweep (sweep/sweep_plan.hpp, kind "stress"): one case per group (its cases build
// their scenes in code, so a case names no scene file), measured by the "stress" measure, and the report
// `sandbox stress` writes: stress.csv and stress.md.
#include "stress/stress_suite.hpp"
#include "sweep/sweep_plan.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sandbox {

/// The plan: one case per group (all of them when `groups` is empty). Throws deform::InputError naming
/// --group for an unknown one.
SweepPlan planStress(const std::vector<std::string>& groups, bool quick);

/// One group run (the "stress" measure): {"cases": [{group, name, checks, passed, detail, seconds}, ...]}.
nlohmann::json measureStressGroup(const std::string& group, bool quick);

/// The cases back from a group's measure (deform::InputError naming `what` for a malformed one).
std::vector<StressCase> stressCasesOf(const nlohmann::json& measured, const std::string& what);

/// Prints each case, writes stress.csv and stress.md into `dir`; returns how many cases failed.
int writeStressReport(const std::vector<StressCase>& cases, bool quick, const std::string& dir);

/// writeStressReport from a stress plan and each case's measure; throws CommandFailure when a stress case
/// failed (after writing the report, as `sandbox stress` does).
void writeStressSweepReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                            const std::string& dir);

}  // namespace sandbox
