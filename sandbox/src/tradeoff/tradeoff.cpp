#include "tradeoff/tradeoff.hpp"

#include <scenes/car_skin.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace sandbox {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kFrameRate_hz = 60.0;  // a game frame: the unit of cost
constexpr const char* kKnobPath = "vehicle.deformation.";

struct Knob {
  std::string name;                 ///< scene key under vehicle.deformation (or physics_hz)
  std::vector<std::string> values;  ///< JSON values
};

std::vector<Knob> sweep(bool quick) {
  if (quick) {
    return {{"control_points", {"30", "250"}}, {"k_nearest", {"4", "0"}},  {"alpha", {"2", "5"}},
            {"substeps", {"1", "8"}},          {"iterations", {"1", "4"}}, {"physics_hz", {"120", "2000"}}};
  }
  return {{"control_points", {"8", "30", "60", "120", "250", "500", "1000"}},
          {"k_nearest", {"1", "4", "8", "16", "0"}},
          {"alpha", {"1", "2", "3.5", "5", "8"}},
          {"substeps", {"1", "2", "4", "8", "16"}},
          {"iterations", {"1", "2", "4", "8"}},
          {"physics_hz", {"120", "240", "500", "1000", "2000"}}};
}

std::vector<std::string> referenceOverrides(bool quick) {
  const std::string d = kKnobPath;
  return {d + "control_points=" + (quick ? "250" : "1000"), d + "k_nearest=0", d + "substeps=8",
          d + "iterations=4", "physics_hz=2000"};
}

std::string overridePath(const std::string& knob) {
  return knob == "physics_hz" ? knob : std::string(kKnobPath) + knob;
}

// What a measured run leaves behind for the error.
struct Played {
  TradeoffRow row;
  std::vector<Eigen::Vector3f> vertices_m;  ///< render mesh at the end, vehicle frame
  double diagonal_m = 0;
};

Played play(const std::string& scene_name, const std::vector<std::string>& overrides) {
  std::vector<scenes::Override> parsed;
  for (const std::string& o : overrides) parsed.push_back(scenes::parseOverride(o));
  const scenes::SceneConfig scene = scenes::loadScene(scene_name, parsed);
  scenes::SceneRun run(scene);
  const vehicle::CarId car = run.carId(0);
  vehicle::Simulation& simulation = run.simulation();
  scenes::CarSkin skin(run.model(0).body, simulation.controlRestPoints(car),
                       simulation.deformationSettings(car));
  const auto frames = static_cast<long>(std::llround(scene.duration_s * kFrameRate_hz));
  double embed_ms = 0;
  for (long f = 1; f <= frames; ++f) {
    run.stepUntil(static_cast<double>(f) / kFrameRate_hz);
    const auto t0 = Clock::now();
    skin.update(simulation.controlDisplacements(car));
    embed_ms += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  }
  run.runToEnd();
  skin.update(simulation.controlDisplacements(car));

  Played p;
  TradeoffRow& r = p.row;
  r.scene = scene.name;
  r.overrides = overrides;
  const double n = static_cast<double>(std::max<long>(frames, 1));
  r.physics_ms = run.times().physics_ms / n;
  r.deform_ms = run.times().deform_ms / n;
  r.embed_ms = embed_ms / n;
  r.residual_crush_m = simulation.metrics(car).residual_crush_m;
  r.strain_residual =
      deform::constraintStrainRms(simulation.body(car).settings(), simulation.body(car).state());
  p.vertices_m = skin.mesh().positions_m;
  p.diagonal_m = deform::boundingBox(run.model(0).body).diagonal_m();
  return p;
}

void setError(TradeoffRow& row, const Played& run, const Played& reference) {
  double sum2 = 0, worst2 = 0;
  for (std::size_t j = 0; j < run.vertices_m.size(); ++j) {
    const double d2 = (run.vertices_m[j] - reference.vertices_m[j]).cast<double>().squaredNorm();
    sum2 += d2;
    worst2 = std::max(worst2, d2);
  }
  const double rms_m = std::sqrt(sum2 / static_cast<double>(std::max<std::size_t>(run.vertices_m.size(), 1)));
  row.rms_error_mm = 1e3 * rms_m;
  row.max_error_mm = 1e3 * std::sqrt(worst2);
  row.rms_error_fraction = rms_m / reference.diagonal_m;
  row.max_error_fraction = std::sqrt(worst2) / reference.diagonal_m;
  row.crush_error_mm = 1e3 * std::abs(row.residual_crush_m - reference.row.residual_crush_m);
}

// Pareto front of one scene's rows: none cheaper and at least as accurate (the reference excluded).
void markPareto(std::vector<TradeoffRow>& rows, std::size_t begin) {
  for (std::size_t i = begin; i < rows.size(); ++i) {
    if (rows[i].knob == "reference") continue;
    bool dominated = false;
    for (std::size_t j = begin; j < rows.size() && !dominated; ++j) {
      if (j == i || rows[j].knob == "reference") continue;
      const bool no_worse =
          rows[j].total_ms() <= rows[i].total_ms() && rows[j].rms_error_mm <= rows[i].rms_error_mm;
      const bool better =
          rows[j].total_ms() < rows[i].total_ms() || rows[j].rms_error_mm < rows[i].rms_error_mm;
      dominated = no_worse && better;
    }
    rows[i].pareto = !dominated;
  }
}

void printRow(const TradeoffRow& r) {
  std::printf(
      "  %-16s %-8s %8.3f ms/frame (physics %.3f, deform %.3f, embed %.3f)  RMS %7.2f mm, max %7.1f mm, "
      "crush %.3f m\n",
      r.knob.c_str(), r.value.c_str(), r.total_ms(), r.physics_ms, r.deform_ms, r.embed_ms, r.rms_error_mm,
      r.max_error_mm, r.residual_crush_m);
  std::fflush(stdout);
}

}  // namespace

std::vector<TradeoffRow> runTradeoff(const TradeoffOptions& options) {
  std::vector<TradeoffRow> rows;
  for (const std::string& scene : options.scenes) {
    const std::size_t begin = rows.size();
    const scenes::SceneConfig as_shipped = scenes::loadScene(scene);
    if (as_shipped.vehicles.size() != 1) {
      throw deform::InputError(as_shipped.source + ": tradeoff measures one car; this scene has " +
                               std::to_string(as_shipped.vehicles.size()));
    }
    std::printf("%s: reference run\n", scene.c_str());
    std::fflush(stdout);
    const Played reference = play(scene, referenceOverrides(options.quick));
    const auto add = [&](const std::string& knob, const std::string& value, const Played& run) {
      TradeoffRow row = run.row;
      row.knob = knob;
      row.value = value;
      setError(row, run, reference);
      printRow(row);
      rows.push_back(row);
    };
    add("reference", "top", reference);
    for (const char* preset : {"fast", "balanced", "accurate"}) {
      add("preset", preset, play(scene, {std::string(kKnobPath) + "preset=" + preset}));
    }
    for (const Knob& knob : sweep(options.quick)) {
      for (const std::string& value : knob.values) {
        const std::string shown = knob.name == "k_nearest" && value == "0" ? "dense" : value;
        add(knob.name, shown, play(scene, {overridePath(knob.name) + "=" + value}));
      }
    }
    markPareto(rows, begin);
  }
  return rows;
}

}  // namespace sandbox
