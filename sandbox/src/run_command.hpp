#pragma once
// `sandbox run` and `sandbox export` as functions (the commands call them; tests too).
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace sandbox {

struct RunOptions {
  std::string scene;         ///< a scene file or a shipped scene's name
  std::string out;           ///< output folder; empty: out/<scene name>
  bool frames = false;       ///< PNG frames (or as the scene says)
  bool video = false;        ///< MP4 (or as the scene says)
  bool heatmap = false;      ///< heat-map colours (or as the scene says)
  std::optional<int> width;  ///< picture size [px]; default the scene's
  std::optional<int> height;
  std::optional<double> fps;      ///< frames per second; default the scene's
  std::vector<std::string> sets;  ///< key.path=value overrides
  bool progress = true;           ///< a progress bar when stderr is a terminal
  /// --save-state T FILE: the two values as given (T in simulated seconds); empty when not asked.
  std::vector<std::string> save_state;
  std::string resume;  ///< --resume FILE: continue from this state file; empty: from the start
  /// --threads N: threads for the cars' deformation (overrides the scene's key threads); none: the
  /// scene's, else the machine's cores.
  std::optional<int> threads;
  /// --budget-ms B: the deformation budget per physics step (the scene key deformation_budget_ms, set as
  /// an override so that a saved state remembers it).
  std::optional<double> budget_ms;
};

struct RunResult {
  nlohmann::json summary;  ///< what summary.json holds
  std::string out_dir;     ///< where it was written
  int frames = 0;          ///< frames rendered (0 headless)
  std::string video_path;  ///< the MP4, empty when none
};

/// Plays the scene and writes DIR/summary.json, DIR/timeline.csv and, when asked, DIR/frames/NNNNN.png
/// and DIR/video.mp4. Throws deform::InputError for bad input (before anything runs),
/// std::runtime_error when the run diverged (after writing the summary that says so) or output failed.
RunResult runScene(const RunOptions& options);

struct ExportOptions {
  std::string scene;
  double at_s = 0;      ///< simulated time of the snapshot [s]
  std::string out;      ///< .glb or .obj
  std::size_t car = 0;  ///< which car
  std::vector<std::string> sets;
  std::string frame = "vehicle";  ///< "vehicle" (the car's own frame) or "world" (placed at its pose)
};

/// Plays the scene headless up to at_s and writes car `car`'s damaged body (and wheels) to `out`, in the
/// vehicle frame or, with frame "world", moved rigidly to the car's pose at that time.
void exportScene(const ExportOptions& options);

}  // namespace sandbox
