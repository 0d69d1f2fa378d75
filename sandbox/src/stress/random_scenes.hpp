#pragma once
// Random crash scenes for `sandbox stress --random` (DESIGN.md section 7: chosen cases pass because they
// were chosen). Each scene is a scene file's JSON object, valid for the scene reader and SceneRun (no car
// overlaps anything at the start), with every car aimed at an obstacle or another car so that it hits it
// within the scene's duration. Scene `index` of seed `seed` depends on those two numbers alone: the same on
// any machine (std::mt19937_64 with our own mapping to numbers, every value rounded before it is used) and
// whatever number of scenes is asked for.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace sandbox {

/// What a random scene holds, in words for the campaign's table ("/" between the cars).
struct RandomSceneOutline {
  std::size_t cars = 0;
  std::string speeds_kmh;  ///< start speed of each car, "56/0/120"
  std::string targets;     ///< what each car is aimed at: "post", "wall", "car0", ...
  double physics_hz = 0;   ///< the scene's physics rate [Hz]
  std::string presets;     ///< each car's deformation preset
  std::string couplings;   ///< each car's coupling (crush, visual)
};

struct RandomScene {
  std::string name;         ///< randomSceneName(seed, index): the scene's name and its file's stem
  nlohmann::json document;  ///< the scene file's object
  RandomSceneOutline outline;
};

/// Scene `index` of seed `seed`.
RandomScene randomScene(uint64_t seed, std::size_t index);

/// "random_<seed>_<index>".
std::string randomSceneName(uint64_t seed, std::size_t index);

}  // namespace sandbox
