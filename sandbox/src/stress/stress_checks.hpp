#pragma once
// The invariants a stress case checks on a finished scene run (DESIGN.md section 7).
#include <scenes/scene_run.hpp>

#include <string>

namespace sandbox {

/// Accumulates what failed; ok while nothing did.
struct RunVerdict {
  bool ok = true;
  std::string failures;  ///< "; "-separated
  std::string figures;   ///< what was measured, for the table
  void fail(const std::string& what) {
    ok = false;
    failures += (failures.empty() ? "" : "; ") + what;
  }
  /// "FAILED: ...; figures" or the figures alone.
  std::string text() const {
    if (ok) return figures;
    return "FAILED: " + failures + (figures.empty() ? "" : "; " + figures);
  }
};

/// Every car of `run`: no divergence (finite, nothing beyond 1e10: the vehicle side's check, and every
/// control point's and the chassis's position here again), no tunnelling, the largest deviation within
/// the visual constraint, and with the crush coupling energy not created (plastic work at most the crush
/// work and the balance both within 2 % of the impact energy plus 1 J).
RunVerdict checkRun(const scenes::SceneRun& run);

}  // namespace sandbox
