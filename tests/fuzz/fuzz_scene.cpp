// libFuzzer target: the scene loader as `sandbox run FILE --set ...` uses it (scenes::parseSceneText and
// scenes::parseOverride). Input: the scene's JSON text, then optional --set texts, each after a NUL byte.
// A refused input (deform::InputError) is the loader working; any other exception, crash, sanitizer report
// or a scene that passed the checks with values outside their documented ranges is a finding.
#include <deform/error.hpp>
#include <scenes/scene_file.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "cpu_budget.hpp"

namespace {

/// Invariants every accepted scene keeps (scenes/README.md's ranges): a hard stop when one fails.
void checkAccepted(const scenes::SceneConfig& scene) {
  const bool ok = std::isfinite(scene.duration_s) && scene.duration_s > 0 && scene.duration_s <= 1e5 &&
                  std::isfinite(scene.physics_hz) && scene.physics_hz >= 15 && scene.physics_hz <= 20000 &&
                  !scene.vehicles.empty();
  if (!ok) std::abort();
  for (const scenes::VehicleConfig& v : scene.vehicles) {
    if (!(std::isfinite(v.mass_kg) && v.mass_kg > 0) || v.mesh.empty()) std::abort();
    if (v.deformation.settings.control_points < 4 || v.deformation.settings.control_points > 5000)
      std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fuzz_support::CpuBudget budget;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t end_of_json = input.find('\0');
  const std::string text = input.substr(0, end_of_json);
  try {
    std::vector<scenes::Override> overrides;
    for (std::size_t at = end_of_json; at != std::string::npos && at < input.size();) {
      const std::size_t next = input.find('\0', at + 1);
      overrides.push_back(
          scenes::parseOverride(input.substr(at + 1, next == std::string::npos ? next : next - at - 1)));
      at = next;
    }
    checkAccepted(scenes::parseSceneText(text, "fuzz.json", overrides, scenes::shippedScenesDir()));
  } catch (const deform::InputError&) {
    // refused with a message: what bad input must get
  }
  return 0;
}
