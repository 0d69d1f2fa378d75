#include "stress/random_campaign.hpp"

#include "elapsed.hpp"

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>
#include <deform/path_checks.hpp>

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "stress/random_checks.hpp"
#include "table_output.hpp"

namespace fs = std::filesystem;

namespace sandbox {
namespace {

struct PlayedRun {
  RunVerdict verdict;
  RandomRunFigures figures;
  uint64_t hash = 0;
};

PlayedRun play(const scenes::SceneConfig& config) {
  scenes::SceneRun run(config);
  const std::vector<CarTrace> traces = playTraced(run);
  PlayedRun played;
  played.verdict = checkRandomRun(run, traces, played.figures);
  played.hash = run.stateHash();
  return played;
}

}  // namespace

RandomOutcome runRandomScene(uint64_t seed, std::size_t index) {
  const auto start = Clock::now();
  RandomOutcome outcome;
  outcome.index = index;
  outcome.scene = randomScene(seed, index);
  try {
    const scenes::SceneConfig config =
        scenes::parseScene(outcome.scene.document, outcome.scene.name + ".json");
    const PlayedRun first = play(config);
    const PlayedRun second = play(config);
    RunVerdict verdict = first.verdict;
    if (second.hash != first.hash) verdict.fail("state hash differs between two runs");
    outcome.passed = verdict.ok;
    outcome.failures = verdict.failures;
    outcome.created_percent = first.figures.created_percent;
    outcome.car_balance_percent = first.figures.car_balance_percent;
    outcome.max_rise_m = first.figures.max_rise_m;
    outcome.impacted = first.figures.impacted;
  } catch (const deform::InputError& e) {
    outcome.failures = std::string("refused by the scene reader (a generator bug): ") + e.what();
  } catch (const std::exception& e) {
    outcome.failures = std::string("threw: ") + e.what();
  }
  outcome.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return outcome;
}

std::vector<RandomOutcome> runRandomCampaign(uint64_t seed, std::size_t first, std::size_t count,
                                             const std::function<void(const RandomOutcome&)>& on_scene) {
  std::vector<RandomOutcome> outcomes;
  for (std::size_t i = first; i < first + count; ++i) {
    outcomes.push_back(runRandomScene(seed, i));
    if (on_scene) on_scene(outcomes.back());
  }
  return outcomes;
}

std::string randomTableHeader() {
  char text[256];
  std::snprintf(text, sizeof text, "%-5s %-4s %-13s %-32s %6s %-24s %-20s %9s %9s %7s %6s  %s", "#", "cars",
                "km/h", "aimed at", "Hz", "preset", "coupling", "created%", "car bal%", "rise m", "verdict",
                "failed");
  return text;
}

std::string randomTableRow(const RandomOutcome& o) {
  const RandomSceneOutline& s = o.scene.outline;
  char text[256];
  std::snprintf(text, sizeof text, "%-5zu %-4zu %-13s %-32s %6.0f %-24s %-20s %9.1f %9.1f %7.2f %6s  ",
                o.index, s.cars, s.speeds_kmh.c_str(), s.targets.c_str(), s.physics_hz, s.presets.c_str(),
                s.couplings.c_str(), o.created_percent, o.car_balance_percent, o.max_rise_m,
                o.passed ? "ok" : "FAIL");
  return text + (o.passed ? std::string(o.impacted == 0 ? "(no impact)" : "") : o.failures);
}

void makeRandomOutputFolder(const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec || !deform::isDirectory(out_dir))
    throw deform::InputError("--out: cannot create folder " + out_dir +
                             (ec ? " (" + ec.message() + ")" : ""));
}

void writeFailingScene(const RandomOutcome& outcome, const std::string& out_dir) {
  if (outcome.passed) return;
  scenes::writeFileAtomically((fs::path(out_dir) / (outcome.scene.name + ".json")).string(),
                              outcome.scene.document.dump(2) + "\n");
}

void writeRandomCsv(const std::vector<RandomOutcome>& outcomes, const std::string& out_dir) {
  CsvTable table({"index", "scene", "cars", "speeds_kmh", "aimed_at", "physics_hz", "presets", "couplings",
                  "impacted_cars", "created_percent", "car_balance_percent", "max_rise_m", "passed", "failed",
                  "seconds"});
  for (const RandomOutcome& o : outcomes) {
    const RandomSceneOutline& s = o.scene.outline;
    table.addRow({std::to_string(o.index), o.scene.name, std::to_string(s.cars), s.speeds_kmh, s.targets,
                  CsvTable::number(s.physics_hz), s.presets, s.couplings, std::to_string(o.impacted),
                  CsvTable::number(o.created_percent), CsvTable::number(o.car_balance_percent),
                  CsvTable::number(o.max_rise_m), o.passed ? "yes" : "no", o.failures,
                  CsvTable::fixed(o.seconds, 2)});
  }
  scenes::writeFileAtomically((fs::path(out_dir) / "stress_random.csv").string(), table.text());
}

}  // namespace sandbox
