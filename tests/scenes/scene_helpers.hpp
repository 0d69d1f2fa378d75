#pragma once
// What the scene tests share: a shipped scene loaded with `--set` overrides.
#include <scenes/scene_file.hpp>

#include <string>
#include <vector>

namespace scene_test {

/// The shipped scene `name` with the overrides `sets` ("path=value", as `--set` takes them).
inline scenes::SceneConfig scene(const std::string& name, const std::vector<std::string>& sets) {
  std::vector<scenes::Override> overrides;
  for (const std::string& s : sets) overrides.push_back(scenes::parseOverride(s));
  return scenes::loadScene(name, overrides);
}

}  // namespace scene_test
