#include "tradeoff/tradeoff.hpp"

#include "elapsed.hpp"

#include "build_version.hpp"
#include "sweep/sweep_case.hpp"

#include <scenes/car_skin.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace sandbox {
namespace {

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

// A case's measure (measureTradeoffCase) back as a row and its render mesh.
Played played(const SweepCase& sweep_case, const nlohmann::json& measured) {
  const std::string what = "case " + sweep_case.id;
  const auto number = [&](const char* name) { return measuredNumber(measured, name, what); };
  const auto text = [&](const char* name) {
    const auto it = measured.find(name);
    if (it == measured.end() || !it->is_string())
      throw deform::InputError(what + ": measured." + name + ": missing or not a string");
    return it->get<std::string>();
  };
  if (!measured.is_object()) throw deform::InputError(what + ": no measure");
  Played p;
  TradeoffRow& r = p.row;
  r.scene = text("scene_name");
  r.overrides = sweep_case.overrides;
  r.physics_ms = number("physics_ms");
  r.deform_ms = number("deform_ms");
  r.embed_ms = number("embed_ms");
  r.residual_crush_m = number("residual_crush_m");
  r.strain_residual = number("strain_residual");
  p.diagonal_m = number("diagonal_m");
  p.vertices_m = decodePoints(text("render_mesh_m"), what + ": measured.render_mesh_m");
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

std::string label(const nlohmann::json& labels, const char* name) {
  const auto it = labels.find(name);
  return it != labels.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

SweepPlan planTradeoff(const TradeoffOptions& options) {
  SweepPlan plan;
  plan.kind = "tradeoff";
  plan.version = buildVersion();
  plan.options = {{"scenes", options.scenes}, {"quick", options.quick}, {"sets", options.sets}};
  std::vector<scenes::Override> sets;
  for (const std::string& set : options.sets) sets.push_back(scenes::parseOverride(set));
  for (const std::string& scene : options.scenes) {
    const scenes::SceneConfig as_set = scenes::loadScene(scene, sets);
    if (as_set.vehicles.size() != 1) {
      throw deform::InputError(as_set.source + ": tradeoff measures one car; this scene has " +
                               std::to_string(as_set.vehicles.size()));
    }
    const auto add = [&](const std::string& knob, const std::string& value, std::vector<std::string> own) {
      std::vector<std::string> overrides = options.sets;
      overrides.insert(overrides.end(), own.begin(), own.end());
      addCase(plan, scene, overrides, "tradeoff", {{"knob", knob}, {"value", value}});
    };
    add("reference", "top", referenceOverrides(options.quick));
    for (const char* preset : {"fast", "balanced", "accurate"}) {
      add("preset", preset, {std::string(kKnobPath) + "preset=" + preset});
    }
    for (const Knob& knob : sweep(options.quick)) {
      for (const std::string& value : knob.values) {
        const std::string shown = knob.name == "k_nearest" && value == "0" ? "dense" : value;
        add(knob.name, shown, {overridePath(knob.name) + "=" + value});
      }
    }
  }
  return plan;
}

nlohmann::json measureTradeoffCase(const std::string& scene_name, const std::vector<std::string>& overrides) {
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

  const double n = static_cast<double>(std::max<long>(frames, 1));
  return {{"scene_name", scene.name},
          {"physics_ms", run.times().physics_ms() / n},
          {"deform_ms", run.times().deformation_ms() / n},
          {"embed_ms", embed_ms / n},
          {"residual_crush_m", simulation.metrics(car).residual_crush_m},
          {"strain_residual",
           deform::constraintStrainRms(simulation.body(car).settings(), simulation.body(car).state())},
          {"diagonal_m", deform::boundingBox(run.model(0).body).diagonal_m()},
          {"render_mesh_m", encodePoints(skin.positions())}};
}

std::vector<TradeoffRow> assembleTradeoff(const SweepPlan& plan,
                                          const std::vector<nlohmann::json>& measured) {
  if (measured.size() != plan.cases.size()) throw std::logic_error("assembleTradeoff: one measure per case");
  std::vector<TradeoffRow> rows;
  std::size_t i = 0;
  while (i < plan.cases.size()) {
    // One scene's cases: those that follow with the same scene.
    std::size_t end = i;
    while (end < plan.cases.size() && plan.cases[end].scene == plan.cases[i].scene) ++end;
    std::size_t reference_index = end;
    for (std::size_t k = i; k < end; ++k)
      if (label(plan.cases[k].labels, "knob") == "reference") reference_index = k;
    if (reference_index == end)
      throw deform::InputError("tradeoff plan: scene " + plan.cases[i].scene + " has no reference case");
    const Played reference = played(plan.cases[reference_index], measured[reference_index]);
    const std::size_t begin = rows.size();
    for (std::size_t k = i; k < end; ++k) {
      const Played run = k == reference_index ? reference : played(plan.cases[k], measured[k]);
      if (run.vertices_m.size() != reference.vertices_m.size()) {
        throw deform::InputError("case " + plan.cases[k].id + ": render mesh of " +
                                 std::to_string(run.vertices_m.size()) + " points, the reference's has " +
                                 std::to_string(reference.vertices_m.size()));
      }
      TradeoffRow row = run.row;
      row.knob = label(plan.cases[k].labels, "knob");
      row.value = label(plan.cases[k].labels, "value");
      setError(row, run, reference);
      rows.push_back(row);
    }
    markPareto(rows, begin);
    i = end;
  }
  return rows;
}

std::vector<TradeoffRow> runTradeoff(const TradeoffOptions& options) {
  const SweepPlan plan = planTradeoff(options);
  std::vector<nlohmann::json> measured;
  for (const SweepCase& c : plan.cases) {
    std::printf("%s: %s %s\n", c.scene.c_str(), label(c.labels, "knob").c_str(),
                label(c.labels, "value").c_str());
    std::fflush(stdout);
    measured.push_back(measureTradeoffCase(c.scene, c.overrides));
  }
  std::vector<TradeoffRow> rows = assembleTradeoff(plan, measured);
  for (const TradeoffRow& r : rows) printRow(r);
  return rows;
}

}  // namespace sandbox
