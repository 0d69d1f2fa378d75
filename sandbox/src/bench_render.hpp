#pragma once
// `sandbox bench render`: the offscreen frames of a scene run, timed by stage (render, readback, encode),
// as `sandbox run` draws and writes them.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace sandbox {

struct RenderBenchOptions {
  std::string scene = "wall_crash";  ///< a scene file or a shipped scene's name
  std::vector<std::string> sets;     ///< key.path=value overrides of the scene
  int frames = 24;                   ///< timed frames, spread evenly over the scene's frame times
  int warmup = 1;                    ///< frames drawn first and not timed (shader compilation)
  int width = 1280;                  ///< picture size [px]
  int height = 720;
  std::optional<int> samples;                ///< MSAA samples; default the scene's
  std::string encode = "video";              ///< "video" (MP4 through ffmpeg), "png" or "none"
  std::string out_dir = "out/bench_render";  ///< where the video or the PNG frames go
};

/// Steps the scene (untimed) to each frame's time and draws, reads back and encodes the frame, timing
/// each stage. Returns {scene, width, height, frames, warmup, encode, renderer, ms_per_frame: {render,
/// readback, encode, total}, embed_ms_per_frame}; means over the timed frames. Encode is what the render
/// loop waits for the worker that finishes (edge smoothing) and encodes the frames, the video's closing
/// (ffmpeg draining its queue) shared among them. Throws deform::InputError for bad options.
nlohmann::ordered_json runRenderBench(const RenderBenchOptions& options);

/// The bench's result as the command prints it: a header line, then one line per stage.
std::string renderBenchText(const nlohmann::ordered_json& result);

}  // namespace sandbox
