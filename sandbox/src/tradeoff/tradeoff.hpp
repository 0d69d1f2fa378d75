#pragma once
// Speed against accuracy (DESIGN.md section 6): one scene played at the top of every knob (the
// reference), then with one knob at a time moved from the balanced preset, and each run's cost per frame
// and error against the reference measured on the render mesh.
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
  bool quick = false;  ///< fewer values per knob and a lighter reference
};

/// The reference and sweep of every scene, Pareto flags set per scene. Progress lines go to stdout.
/// Throws deform::InputError for a scene with more than one car.
std::vector<TradeoffRow> runTradeoff(const TradeoffOptions& options);

}  // namespace sandbox
