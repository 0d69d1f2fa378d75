// `sandbox bench render`: frames of a scene run, drawn, read back and encoded as `sandbox run` does, with
// the time of each stage per frame.
#include "bench_render.hpp"

#include "elapsed.hpp"

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "frame_writer.hpp"
#include "render/png_io.hpp"
#include "render/video_writer.hpp"
#include "run_render.hpp"

namespace fs = std::filesystem;

namespace sandbox {
namespace {

void check(const RenderBenchOptions& o) {
  if (o.frames < 1 || o.frames > 100000) throw deform::InputError("--frames: must be in [1, 100000]");
  if (o.warmup < 0 || o.warmup > 1000) throw deform::InputError("--warmup: must be in [0, 1000]");
  if (o.width < 16 || o.width > 8192 || o.height < 16 || o.height > 8192)
    throw deform::InputError("--width/--height: must be in [16, 8192] pixels");
  if (o.samples && (*o.samples < 0 || *o.samples > 64))
    throw deform::InputError("--samples: must be in [0, 64]");
  if (o.encode != "video" && o.encode != "png" && o.encode != "none")
    throw deform::InputError("--encode: must be video, png or none (got '" + o.encode + "')");
}

}  // namespace

nlohmann::ordered_json runRenderBench(const RenderBenchOptions& options) {
  check(options);
  std::vector<scenes::Override> overrides;
  for (const std::string& s : options.sets) overrides.push_back(scenes::parseOverride(s));
  scenes::SceneConfig scene = scenes::loadScene(options.scene, overrides);
  scene.outputs.width = options.width;
  scene.outputs.height = options.height;
  if (options.samples) scene.outputs.samples = *options.samples;
  const fs::path out(options.out_dir);
  if (options.encode != "none") {
    std::error_code ec;
    fs::create_directories(options.encode == "png" ? out / "frames" : out, ec);
    if (ec)
      throw deform::InputError("--out: cannot create folder " + options.out_dir + " (" + ec.message() + ")");
  }

  scenes::SceneRun run(scene);
  scenes::StageTimes& times = run.times();
  RunRenderer renderer(run, scene.outputs, times);
  std::unique_ptr<render::VideoWriter> video;
  if (options.encode == "video") {
    video = std::make_unique<render::VideoWriter>(
        (out / "video.mp4").string(),
        render::VideoSettings{options.width, options.height, scene.outputs.fps});
  }

  // The frame times `sandbox run` draws, and the timed frames spread evenly over them (the crash and
  // the rest both).
  const double frame_dt_s = scene.outputs.playback_speed / scene.outputs.fps;
  const int run_frames = static_cast<int>(std::floor(scene.duration_s / frame_dt_s + 1e-9)) + 1;
  const auto frameTime = [&](int k) {
    if (options.frames == 1) return 0.0;
    const long index = std::lround(static_cast<double>(k) * (run_frames - 1) / (options.frames - 1));
    return static_cast<double>(index) * frame_dt_s;
  };

  // Warm-up: llvmpipe compiles each shader variant on its first draw.
  for (int k = 0; k < options.warmup; ++k) {
    renderer.draw(run, times);
    (void)renderer.readback();
  }

  // As `sandbox run`: each frame smoothed and encoded on a worker while the next one renders; the
  // render loop's wait for it is the encode stage.
  FrameWriter writer([&](render::Image& image, int k) {
    renderer.finishFrame(image);
    if (options.encode == "png") {
      char name[32];
      std::snprintf(name, sizeof name, "%05d.png", k);
      render::writePng((out / "frames" / name).string(), image.width, image.height, image.rgba,
                       render::PngCompression::Fast);
    } else if (video) {
      video->addFrame(image.rgba);
    }
  });

  double render_ms = 0, readback_ms = 0, encode_ms = 0, embed_ms = 0;
  for (int k = 0; k < options.frames; ++k) {
    run.stepUntil(frameTime(k));
    const scenes::StageTimes before = times;
    renderer.draw(run, times);
    auto start = Clock::now();
    renderer.renderer().finish();
    render_ms += times.render_ms - before.render_ms + msSince(start);
    embed_ms += times.embed_ms - before.embed_ms;

    start = Clock::now();
    render::Image image = renderer.readback();
    readback_ms += msSince(start);

    start = Clock::now();
    writer.add(std::move(image), k);
    encode_ms += msSince(start);
  }
  const auto start = Clock::now();
  writer.finish();
  if (video) video->finish();
  encode_ms += msSince(start);

  const double n = options.frames;
  nlohmann::ordered_json result;
  result["scene"] = scene.name;
  result["width"] = options.width;
  result["height"] = options.height;
  result["frames"] = options.frames;
  result["warmup"] = options.warmup;
  result["encode"] = options.encode;
  result["renderer"] = renderer.renderer().description();
  result["ms_per_frame"] = {{"render", render_ms / n},
                            {"readback", readback_ms / n},
                            {"encode", encode_ms / n},
                            {"total", (render_ms + readback_ms + encode_ms) / n}};
  result["embed_ms_per_frame"] = embed_ms / n;
  return result;
}

std::string renderBenchText(const nlohmann::ordered_json& r) {
  std::string text;
  char line[256];
  std::snprintf(line, sizeof line, "render bench: %s, %dx%d, %d frames (+%d warm-up), encode %s\n",
                r["scene"].get<std::string>().c_str(), r["width"].get<int>(), r["height"].get<int>(),
                r["frames"].get<int>(), r["warmup"].get<int>(), r["encode"].get<std::string>().c_str());
  text += line;
  std::snprintf(line, sizeof line, "  %s\n", r["renderer"].get<std::string>().c_str());
  text += line;
  text += "  stage      ms/frame\n";
  for (const char* stage : {"render", "readback", "encode", "total"}) {
    std::snprintf(line, sizeof line, "  %-9s %9.2f\n", stage, r["ms_per_frame"][stage].get<double>());
    text += line;
  }
  std::snprintf(line, sizeof line, "  (embed, not in the total: %.2f ms/frame)\n",
                r["embed_ms_per_frame"].get<double>());
  text += line;
  return text;
}

void registerBenchRenderCommand(CLI::App& bench) {
  auto options = std::make_shared<RenderBenchOptions>();
  auto json = std::make_shared<bool>(false);
  auto* cmd = bench.add_subcommand(
      "render", "Offscreen frames of a scene: ms per frame to render, read back and encode (as `run` does)");
  cmd->add_option("SCENE", options->scene, "Scene file, or a shipped scene's name")->capture_default_str();
  cmd->add_option("--frames", options->frames, "Timed frames, spread over the scene")->capture_default_str();
  cmd->add_option("--warmup", options->warmup, "Untimed frames first")->capture_default_str();
  cmd->add_option("--width", options->width, "Picture width [px]")->capture_default_str();
  cmd->add_option("--height", options->height, "Picture height [px]")->capture_default_str();
  cmd->add_option("--samples", options->samples, "MSAA samples (default the scene's)");
  cmd->add_option("--encode", options->encode, "video (MP4 through ffmpeg), png or none")
      ->capture_default_str();
  cmd->add_option("--out", options->out_dir, "Folder for the video or the PNG frames")->capture_default_str();
  cmd->add_option("--set", options->sets, "Override a scene key: --set duration_s=0.5 (repeatable)")
      ->expected(1)
      ->take_all();
  cmd->add_flag("--json", *json, "Print one JSON object");
  cmd->callback([options, json] {
    const nlohmann::ordered_json result = runRenderBench(*options);
    if (*json) {
      std::printf("%s\n", result.dump(2).c_str());
    } else {
      std::printf("%s", renderBenchText(result).c_str());
    }
  });
}

}  // namespace sandbox
