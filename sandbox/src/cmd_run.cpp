// `sandbox run SCENE`: plays a scene at its fixed physics rate; renders PNG frames and an MP4 at the
// frame rate when asked; writes DIR/summary.json (the run's figures) and DIR/timeline.csv (a row per
// frame). Headless runs never embed the render mesh (DESIGN.md section 8).
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>
#include <deform/path_checks.hpp>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "elapsed.hpp"
#include "frame_writer.hpp"
#include "render/png_io.hpp"
#include "render/video_writer.hpp"
#include "run_command.hpp"
#include "run_render.hpp"

namespace fs = std::filesystem;

namespace sandbox {
namespace {

// A one-line progress bar on stderr, only on a terminal and only once a run takes more than a moment.
class ProgressBar {
 public:
  ProgressBar(std::string label, bool enabled)
      : label_(std::move(label)), enabled_(enabled && isatty(STDERR_FILENO) != 0), start_(Clock::now()) {}
  void update(double fraction, const std::string& detail) {
    if (!enabled_) return;
    const double elapsed = secondsSince(start_);
    if (elapsed < 0.5 || elapsed - last_ < 0.1) return;
    last_ = elapsed;
    shown_ = true;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * kWidth);
    std::fprintf(stderr, "\r%s [%s%s] %3.0f%% %s  ", label_.c_str(),
                 std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), fraction * 100.0,
                 detail.c_str());
    std::fflush(stderr);
  }
  ~ProgressBar() {
    if (shown_) std::fprintf(stderr, "\r\033[K");
  }

 private:
  std::string label_;
  bool enabled_;
  Clock::time_point start_;
  double last_ = 0;
  bool shown_ = false;
};

void applyFlags(const RunOptions& options, scenes::OutputConfig& outputs) {
  if (options.width && (*options.width < 16 || *options.width > 8192)) {
    throw deform::InputError("--width: must be in [16, 8192] pixels (got " + std::to_string(*options.width) +
                             ")");
  }
  if (options.height && (*options.height < 16 || *options.height > 8192)) {
    throw deform::InputError("--height: must be in [16, 8192] pixels (got " +
                             std::to_string(*options.height) + ")");
  }
  if (options.fps && !(*options.fps >= 1 && *options.fps <= 1000)) {
    throw deform::InputError("--fps: must be in [1, 1000] frames per second");
  }
  outputs.frames = outputs.frames || options.frames;
  outputs.video = outputs.video || options.video;
  outputs.heatmap = outputs.heatmap || options.heatmap;
  if (options.width) outputs.width = *options.width;
  if (options.height) outputs.height = *options.height;
  if (options.fps) outputs.fps = *options.fps;
}

fs::path prepareOutput(const std::string& dir, bool frames) {
  const fs::path out(dir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !deform::isDirectory(out))
    throw deform::InputError("--out: cannot create folder " + dir + (ec ? " (" + ec.message() + ")" : ""));
  // Frames and a video of an earlier run must not pass for this run's.
  fs::remove(out / "video.mp4", ec);
  if (deform::isDirectory(out / "frames")) {
    for (const auto& entry : fs::directory_iterator(out / "frames")) {
      if (entry.path().extension() == ".png") fs::remove(entry.path());
    }
  }
  if (frames) fs::create_directories(out / "frames");
  return out;
}

std::vector<scenes::Override> overridesOf(const std::vector<std::string>& sets) {
  std::vector<scenes::Override> overrides;
  for (const std::string& s : sets) overrides.push_back(scenes::parseOverride(s));
  return overrides;
}

/// --save-state's time: a number of simulated seconds within the scene (and not before a resumed state).
double saveTime(const std::vector<std::string>& args, double duration_s, double resumed_s) {
  std::size_t used = 0;
  double t_s = 0;
  try {
    t_s = std::stod(args[0], &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != args[0].size() || !std::isfinite(t_s))
    throw deform::InputError("--save-state: T must be a time in seconds (got '" + args[0] + "')");
  if (t_s < 0 || t_s > duration_s + 1e-9)
    throw deform::InputError("--save-state: T must be within the scene, 0 to " + std::to_string(duration_s) +
                             " s (got " + args[0] + ")");
  const fs::path folder = fs::path(args[1]).parent_path();
  if (!folder.empty() && !deform::isDirectory(folder))
    throw deform::InputError("--save-state: no folder " + folder.string() + " for " + args[1]);
  if (t_s < resumed_s - 1e-9)
    throw deform::InputError("--save-state: T is before the resumed state's time " +
                             std::to_string(resumed_s) + " s (got " + args[0] + ")");
  return t_s;
}

std::string frameName(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "%05d.png", frame);
  return name;
}

}  // namespace

RunResult runScene(const RunOptions& options) {
  const auto started = Clock::now();
  std::vector<scenes::Override> overrides = overridesOf(options.sets);
  if (options.budget_ms) {
    if (!(*options.budget_ms >= 0))
      throw deform::InputError("--budget-ms: must be >= 0 (got " + std::to_string(*options.budget_ms) + ")");
    overrides.push_back(scenes::parseOverride("deformation_budget_ms=" + std::to_string(*options.budget_ms)));
  }
  scenes::SceneConfig scene = scenes::loadScene(options.scene, overrides);
  applyFlags(options, scene.outputs);
  if (options.threads) {
    if (*options.threads < 1)
      throw deform::InputError("--threads: must be >= 1 (got " + std::to_string(*options.threads) + ")");
    scene.threads = options.threads;
  }
  const scenes::OutputConfig outputs = scene.outputs;
  const bool draw = outputs.frames || outputs.video;
  // The meshes load (and may be refused) before the output folder is touched: a refused run leaves an
  // earlier run's files as they were.
  scenes::SceneRun run(scene);
  // A state file to resume from is checked before anything is written, too.
  if (!options.resume.empty()) run.restoreState(options.resume);
  const double resumed_s = run.time_s();
  const bool save = !options.save_state.empty();
  if (save && options.save_state.size() != 2)
    throw deform::InputError("--save-state: needs two values, T and FILE");
  const double save_at_s = save ? saveTime(options.save_state, scene.duration_s, resumed_s) : 0.0;
  bool saved = false;
  double saved_s = 0;
  auto saveNow = [&] {
    run.stepUntil(save_at_s);
    run.saveState(options.save_state[1]);
    saved = true;
    saved_s = run.time_s();
  };
  const fs::path out = prepareOutput(options.out.empty() ? "out/" + scene.name : options.out, outputs.frames);

  scenes::StageTimes& times = run.times();
  // Set-up is everything before the first step: the scene file, the meshes and builds (SceneRun's own
  // share is in times already), the output folder; the renderer's and video's set-up count as render.
  times.setup_ms = secondsSince(started) * 1e3;
  std::unique_ptr<RunRenderer> renderer;
  std::unique_ptr<render::VideoWriter> video;
  const auto render_setup = Clock::now();
  if (draw) renderer = std::make_unique<RunRenderer>(run, outputs, times);
  if (outputs.video) {
    video = std::make_unique<render::VideoWriter>(
        (out / "video.mp4").string(), render::VideoSettings{outputs.width, outputs.height, outputs.fps});
  }

  // Frames are smoothed and written on a worker while the next one renders.
  std::unique_ptr<FrameWriter> writer;
  if (draw) {
    writer = std::make_unique<FrameWriter>([&](render::Image& image, int frame) {
      renderer->finishFrame(image);
      if (outputs.frames)
        render::writePng((out / "frames" / frameName(frame)).string(), image.width, image.height, image.rgba,
                         render::PngCompression::Fast);
      if (video) video->addFrame(image.rgba);
    });
  }
  if (draw) times.render_ms += secondsSince(render_setup) * 1e3;

  // One frame (and timeline row) every playback_speed / fps simulated seconds, from t = 0 to the end.
  const double frame_dt_s = outputs.playback_speed / outputs.fps;
  const int frame_count = static_cast<int>(std::floor(scene.duration_s / frame_dt_s + 1e-9)) + 1;
  std::vector<std::string> columns = run.timelineColumns();
  for (const char* c : {"physics_ms", "deform_ms", "coupling_ms", "metrics_ms", "embed_ms", "render_ms"})
    columns.push_back(c);
  std::vector<std::vector<double>> rows;
  ProgressBar progress(scene.name, options.progress);
  RunResult result;
  scenes::StageTimes before = times;
  // A resumed run's frames (and timeline rows) start at the first frame time not before the state's.
  const double half_step_s = 0.5 / scene.physics_hz;
  for (int frame = 0; frame < frame_count; ++frame) {
    if (frame * frame_dt_s < resumed_s - half_step_s) continue;
    if (save && !saved && frame * frame_dt_s >= save_at_s - half_step_s) saveNow();
    run.stepUntil(frame * frame_dt_s);
    if (renderer) {
      renderer->draw(run, times);
      const auto write_start = Clock::now();
      writer->add(renderer->readback(), frame);
      times.render_ms += secondsSince(write_start) * 1e3;
      ++result.frames;
    }
    const auto row_start = Clock::now();
    std::vector<double> row = run.timelineValues();
    row.insert(row.end(), {times.physics_ms() - before.physics_ms(), times.deform_ms - before.deform_ms,
                           times.coupling_ms - before.coupling_ms, times.metrics_ms - before.metrics_ms,
                           times.embed_ms - before.embed_ms, times.render_ms - before.render_ms});
    before = times;
    rows.push_back(std::move(row));
    times.output_ms += secondsSince(row_start) * 1e3;
    char detail[96];
    std::snprintf(detail, sizeof detail, "t %.2f/%.2f s, frame %d/%d", run.time_s(), scene.duration_s,
                  frame + 1, frame_count);
    progress.update(static_cast<double>(frame + 1) / frame_count, detail);
  }
  if (save && !saved) saveNow();
  run.runToEnd();
  if (writer) {
    const auto finish_start = Clock::now();
    writer->finish();
    times.render_ms += secondsSince(finish_start) * 1e3;
  }
  if (video) {
    const auto finish_start = Clock::now();
    video->finish();
    times.render_ms += secondsSince(finish_start) * 1e3;
    result.video_path = video->path();
  }
  // The files are written last; their time is measured up to the summary's own writing (which cannot
  // hold its own duration).
  const auto output_start = Clock::now();
  const std::string timeline = scenes::timelineCsv(columns, rows);
  scenes::writeFileAtomically((out / "timeline.csv").string(), timeline);
  times.output_ms += secondsSince(output_start) * 1e3;
  times.total_ms = secondsSince(started) * 1e3;

  result.summary = run.summary();
  result.summary["frames"] = result.frames;
  if (renderer) result.summary["embeds_out_of_view"] = renderer->embedsOutOfView();
  result.summary["fps"] = outputs.fps;
  result.summary["playback_speed"] = outputs.playback_speed;
  if (!result.video_path.empty()) result.summary["video"] = result.video_path;
  if (!options.resume.empty())
    result.summary["resumed_from"] = {{"file", options.resume}, {"time_s", resumed_s}};
  if (save) result.summary["saved_state"] = {{"file", options.save_state[1]}, {"time_s", saved_s}};
  result.out_dir = out.string();
  scenes::writeFileAtomically((out / "summary.json").string(), result.summary.dump(2) + "\n");
  if (run.diverged()) {
    throw std::runtime_error(
        scene.name +
        ": the run diverged (a non-finite value, one beyond 1e10, energy created or a car "
        "past its ballistic bound): " +
        run.divergence() + "; see " + (out / "summary.json").string());
  }
  return result;
}

void registerRunCommand(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  auto* run = app.add_subcommand("run", "Play a scene; write summary.json, timeline.csv, frames and video");
  run->add_option("SCENE", options->scene,
                  "Scene file, or a shipped scene's name (wall_crash, pole_side, ...)")
      ->required();
  run->add_option("--out", options->out, "Output folder (default out/<scene name>)");
  run->add_flag("--frames", options->frames, "Write PNG frames to DIR/frames/NNNNN.png");
  run->add_flag("--video", options->video, "Write DIR/video.mp4 (H.264)");
  run->add_flag("--heatmap", options->heatmap, "Colour the car by its displacement (red most, blue none)");
  run->add_option("--width", options->width, "Picture width [px] (default the scene's, 1280)");
  run->add_option("--height", options->height, "Picture height [px] (default the scene's, 720)");
  run->add_option("--fps", options->fps, "Frames per second (default the scene's)");
  run->add_option("--set", options->sets,
                  "Override a scene key: --set vehicle.start.speed_kmh=5 (repeatable)")
      ->expected(1)
      ->take_all();
  run->add_option("--save-state", options->save_state,
                  "Write the whole state at simulated time T to FILE (the run goes on to the end): "
                  "--save-state T FILE")
      ->expected(2)
      ->type_name("T FILE");
  run->add_option("--threads", options->threads,
                  "Threads for the cars' deformation steps (default: the scene's key threads, else the "
                  "machine's cores); the state hash does not depend on it");
  run->add_option("--budget-ms", options->budget_ms,
                  "Deformation budget per physics step, every car together [ms]: each car's level of detail "
                  "is chosen to fit, the first to crash and those near the camera finest (the scene key "
                  "deformation_budget_ms)");
  run->add_option("--resume", options->resume,
                  "Continue from a state file of this scene and these --set values (--save-state's)")
      ->type_name("FILE");
  run->callback([options] {
    const RunResult result = runScene(*options);
    const nlohmann::json& s = result.summary;
    if (s.contains("deformation_budget")) {
      const nlohmann::json& b = s["deformation_budget"];
      std::printf("deformation budget %.3f ms per step: estimated %.3f ms, measured %.3f ms%s\n",
                  b["budget_ms"].get<double>(), b["estimated_ms"].get<double>(),
                  b["measured_ms_per_step"].get<double>(),
                  b["met"].get<bool>() ? "" : " (not met: every car is at the coarsest level it may take)");
    }
    std::printf("%s: %llu steps, %.3f s simulated in %.1f s; state hash %s\n",
                s["scene"].get<std::string>().c_str(),
                static_cast<unsigned long long>(s["steps"].get<uint64_t>()), s["time_s"].get<double>(),
                s["timing_ms"]["total"].get<double>() / 1e3, s["state_hash"].get<std::string>().c_str());
    std::printf(
        "impact %.1f km/h, residual crush %.3f m (max %.3f m; on the car's surface %.3f m), "
        "max dynamic crush %.3f m, restitution %.2f\n",
        s["impact_speed_mps"].get<double>() * 3.6, s["residual_crush_m"].get<double>(),
        s["max_residual_crush_m"].get<double>(), s["surface_residual_crush_m"].get<double>(),
        s["max_dynamic_crush_m"].get<double>(), s["restitution"].get<double>());
    const nlohmann::json& ms = s["timing_ms"];
    std::printf(
        "timing: setup %.0f ms, physics %.0f ms (tyres %.0f, collide %.0f, solve %.0f), deform %.0f ms, "
        "coupling %.0f ms, metrics %.0f ms, embed %.0f ms, render %.0f ms, output %.0f ms, total %.0f ms\n",
        ms["setup"].get<double>(), ms["physics"].get<double>(), ms["tyres"].get<double>(),
        ms["collide"].get<double>(), ms["solve"].get<double>(), ms["deform"].get<double>(),
        ms["coupling"].get<double>(), ms["metrics"].get<double>(), ms["embed"].get<double>(),
        ms["render"].get<double>(), ms["output"].get<double>(), ms["total"].get<double>());
    if (s.contains("resumed_from"))
      std::printf("resumed from %s at t = %.4f s\n", options->resume.c_str(),
                  s["resumed_from"]["time_s"].get<double>());
    if (s.contains("saved_state"))
      std::printf("saved the state at t = %.4f s to %s\n", s["saved_state"]["time_s"].get<double>(),
                  options->save_state[1].c_str());
    std::printf("wrote %s/summary.json, %s/timeline.csv", result.out_dir.c_str(), result.out_dir.c_str());
    if (s.contains("frames") && result.frames > 0 &&
        deform::isDirectory(fs::path(result.out_dir) / "frames") &&
        !fs::is_empty(fs::path(result.out_dir) / "frames")) {
      std::printf(", %d frames in %s/frames", result.frames, result.out_dir.c_str());
    }
    if (!result.video_path.empty()) std::printf(", video %s", result.video_path.c_str());
    std::printf("\n");
  });
}

}  // namespace sandbox
