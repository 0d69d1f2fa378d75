// `sandbox bench cars`: the runs (cars_bench.hpp).
#include "cars_bench.hpp"

#include "elapsed.hpp"

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <map>

namespace sandbox {

std::string cruisingCarsScene(std::size_t cars, double duration_s, double physics_hz, bool skip_when_idle) {
  constexpr std::size_t kLanes = 10;
  constexpr double kLaneWidth_m = 4.0, kRowGap_m = 15.0;
  nlohmann::json vehicles = nlohmann::json::array();
  for (std::size_t i = 0; i < cars; ++i) {
    const double x_m = kRowGap_m * static_cast<double>(i / kLanes);
    const double y_m = kLaneWidth_m * static_cast<double>(i % kLanes);
    vehicles.push_back({{"name", "car" + std::to_string(i)},
                        {"mesh", "builtin:sedan?vertices=20000"},
                        {"mass_kg", 1500},
                        {"coupling", "crush"},
                        {"start", {{"position_m", {x_m, y_m}}, {"heading_deg", 0}, {"speed_kmh", 50}}},
                        {"drive", {{"target_speed_kmh", 50}}},
                        {"deformation", {{"skip_when_idle", skip_when_idle}}}});
  }
  const nlohmann::json scene = {
      {"description", std::to_string(cars) + " built-in sedans cruising at 50 km/h, no obstacle"},
      {"duration_s", duration_s},
      {"physics_hz", physics_hz},
      {"vehicles", vehicles}};
  return scene.dump(1);
}

std::vector<CarsBenchRow> runCarsBench(const CarsBenchOptions& options) {
  std::vector<CarsBenchRow> rows;
  for (std::size_t cars : options.cars) {
    const std::string text =
        cruisingCarsScene(cars, options.duration_s, options.physics_hz, options.skip_when_idle);
    for (int threads : options.threads) {
      scenes::SceneConfig scene = scenes::parseSceneText(text, "bench_cars_" + std::to_string(cars), {}, ".");
      scene.threads = threads;
      scene.deformation_budget_ms = options.budget_ms;
      const auto start = Clock::now();
      scenes::SceneRun run(scene);
      const auto stepping = Clock::now();
      run.runToEnd();
      const auto end = Clock::now();
      const scenes::StageTimes& t = run.times();
      const double per_s = 1.0 / run.time_s();
      CarsBenchRow row;
      row.cars = cars;
      row.threads = threads;
      row.setup_ms = std::chrono::duration<double, std::milli>(stepping - start).count();
      row.step_ms = std::chrono::duration<double, std::milli>(end - stepping).count() * per_s;
      row.tyres_ms = t.tyres_ms * per_s;
      row.collide_ms = t.collide_ms * per_s;
      row.solve_ms = t.solve_ms * per_s;
      row.deform_ms = t.deform_ms * per_s;
      row.coupling_ms = t.coupling_ms * per_s;
      row.metrics_ms = t.metrics_ms * per_s;
      row.state_hash = scenes::hashHex(run.stateHash());
      if (run.budgetPlan()) {
        row.budget_estimated_ms = run.budgetPlan()->estimated_ms;
        row.budget_measured_ms = run.steps() > 0 ? t.deform_ms / static_cast<double>(run.steps()) : 0.0;
        std::map<std::string, int> count;
        for (const scenes::BudgetChoice& c : run.budgetPlan()->cars) ++count[c.level];
        for (const auto& [level, n] : count)
          row.levels += (row.levels.empty() ? "" : ", ") + std::to_string(n) + " " + level;
      }
      std::printf(
          "%4zu cars, %d thread%s: set-up %7.1f ms, %7.1f ms per simulated s (%.1fx real time), hash %s\n",
          cars, threads, threads == 1 ? " " : "s", row.setup_ms, row.step_ms, row.realtime_factor(),
          row.state_hash.c_str());
      std::fflush(stdout);
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace sandbox
