#pragma once
// Reading scene files strictly (DESIGN.md section 9): unknown keys, wrong types, values out of range
// and missing files are refused before anything runs, with deform::InputError messages of the form
// "scenes/wall_crash.json: vehicle.start.speed_kmh: must be in [0, 600] (got 900)".
#include <scenes/scene.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace scenes {

/// One `--set key.path=value` override: the path in dots (array items by index, `obstacles.0.x` or
/// `obstacles[0].x`) and the value as JSON text (a bare word that is not JSON counts as a string).
struct Override {
  std::string path;
  std::string value;
};

/// Splits "key.path=value". Throws InputError naming --set when there is no '=' or no path.
Override parseOverride(const std::string& text);

/// Sets `override.path` in `document` (objects along the path are created when missing; array indices
/// must exist, or be one past the end as the last part of the path: that appends). Throws InputError naming
/// --set and the path when the path crosses a non-object value.
void applyOverride(nlohmann::json& document, const Override& override);

/// The scene file for `name_or_path`: an existing file, else a shipped scene's name (`wall_crash` ->
/// <source tree>/scenes/wall_crash.json, or scenes/ next to the binary). Throws InputError naming it
/// when neither exists.
std::string resolveScenePath(const std::string& name_or_path);

/// Folder of the shipped scenes (the source tree's scenes/, set at build time).
std::string shippedScenesDir();

/// Names of the shipped scenes (their file stems), sorted.
std::vector<std::string> shippedSceneNames();

/// Reads, overrides and checks a scene. `source` names it in messages (the path). Relative mesh paths
/// are taken relative to `base_dir`; "${DEFORM_TEST_MESHES}" in a mesh path is replaced by that
/// environment variable (InputError when it is unset, saying how to give the path instead).
SceneConfig parseScene(const nlohmann::json& document, const std::string& source,
                       const std::string& base_dir = ".");

/// resolveScenePath, read the JSON (syntax errors name the file, line and column), applyOverride for
/// each override in order, parseScene, and check that every mesh file exists.
SceneConfig loadScene(const std::string& name_or_path, const std::vector<Override>& overrides = {});

/// What loadScene does once it has the file's text: parse it (syntax errors and duplicate keys name
/// `path`, line and column), applyOverride for each override in order, parseScene against `base_dir`.
/// The scene fuzz target (tests/fuzz/) enters here.
SceneConfig parseSceneText(const std::string& text, const std::string& path,
                           const std::vector<Override>& overrides, const std::string& base_dir);

}  // namespace scenes
