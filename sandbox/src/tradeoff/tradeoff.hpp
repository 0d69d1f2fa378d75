#pragma once
// Speed against accuracy (DESIGN.md section 6): one scene played at the top of every knob (the
// reference), then with one knob at a time moved from the balanced preset, and each run's cost per frame
// and error against the reference measured on the render mesh.
#include "sweep/sweep_plan.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sandbox {

/// One configuration of one scene, measured.
struct TradeoffRow {
  std::string scene;
  std::string knob;                    ///< "reference", "preset", "control_points", "k_nearest", "alpha", ...
  std::string value;                   ///< the knob's value ("250", "dense", "fast")
  std::vector<std::string> overrides;  ///< the --set overrides that make it
  // Cost per 60 Hz frame, by stage [ms].
  double physics_ms = 0, deform_ms = 0, embed_ms = 0;
  double total_ms() const { return physics_ms + deform_ms + embed_ms; }
  // Error against the reference after the scene settles (its end), render mesh in the vehicle frame.
  double rms_error_mm = 0, max_error_mm = 0;
  double rms_error_fraction = 0, max_error_fraction = 0;  ///< of the bounding-box diagonal [-]
  double residual_crush_m = 0;
  double crush_error_mm = 0;   ///< |crush - reference crush|
  double strain_residual = 0;  ///< constraintStrainRms at the end [-]
  bool pareto = false;         ///< no other row of the scene is both cheaper and more accurate
};

struct TradeoffOptions {
  std::vector<std::string> scenes = {"wall_crash", "post_bumps"};
  bool quick = false;             ///< fewer values per knob and a lighter reference
  std::vector<std::string> sets;  ///< scene overrides for every run, before the knob's own
};

/// The sweep as a plan (sweep/sweep_plan.hpp, kind "tradeoff"): per scene the reference, the three presets
/// and one knob at a time, each case measured by measureTradeoffCase. Checks every scene and override
/// first: throws deform::InputError for a bad one or a scene with more than one car.
SweepPlan planTradeoff(const TradeoffOptions& options);

/// One case played frame by frame with the skin (the sweep's "tradeoff" measure): cost per 60 Hz frame by
/// stage, residual crush, strain residual, the bounding-box diagonal and the render mesh at the end.
nlohmann::json measureTradeoffCase(const std::string& scene, const std::vector<std::string>& overrides);

/// The rows from a tradeoff plan and each case's measure (in the plan's order): the error of each
/// against its scene's reference, Pareto flags per scene. Throws deform::InputError naming a case whose
/// measure lacks a field, or a scene without its reference.
std::vector<TradeoffRow> assembleTradeoff(const SweepPlan& plan, const std::vector<nlohmann::json>& measured);

/// planTradeoff, every case measured in this process, assembleTradeoff. Progress lines go to stdout.
std::vector<TradeoffRow> runTradeoff(const TradeoffOptions& options);

/// tradeoff.csv, tradeoff.md and a Pareto plot per scene into `dir` (tradeoff_report.cpp).
void writeTradeoffReport(const std::vector<TradeoffRow>& rows, const std::string& dir);

}  // namespace sandbox
