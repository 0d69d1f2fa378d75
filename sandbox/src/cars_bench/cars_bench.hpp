#pragma once
// `sandbox bench cars` (issue 12): many built-in sedans cruising at 50 km/h under speed control, no
// obstacle, at 60 Hz, for several car counts on one and more threads: set-up time, cost per simulated
// second split by stage, how much faster than real time, and whether the state hash is the same on every
// thread count.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace sandbox {

struct CarsBenchOptions {
  std::vector<std::size_t> cars = {1, 10, 50, 100, 200};
  std::vector<int> threads = {1, 2};
  double duration_s = 5.0;   ///< simulated time per run [s]
  double physics_hz = 60.0;  ///< [Hz]
  std::string out_dir = "out/bench_cars";
  bool skip_when_idle = true;  ///< the cars' vehicle.deformation.skip_when_idle
  /// --budget-ms: the scenes' deformation_budget_ms (a level per car, scenes/deformation_budget.hpp).
  std::optional<double> budget_ms;
};

struct CarsBenchRow {
  std::size_t cars = 0;
  int threads = 1;
  double setup_ms = 0;  ///< scene to first step: meshes, shared builds, world [ms]
  /// Per simulated second [ms/s]: ODE's tyres, collide, solve; the bodies' deform, coupling, metrics.
  double tyres_ms = 0, collide_ms = 0, solve_ms = 0, deform_ms = 0, coupling_ms = 0, metrics_ms = 0;
  double step_ms = 0;  ///< wall time of the stepping per simulated second [ms/s]
  double realtime_factor() const { return step_ms > 0 ? 1000.0 / step_ms : 0; }  ///< x real time
  std::string state_hash;
  /// With a budget: the plan's estimate and deform's measured time per physics step, every car together
  /// [ms], and the levels chosen (e.g. "100 fast").
  double budget_estimated_ms = 0, budget_measured_ms = 0;
  std::string levels;
};

/// The scene it runs: `cars` sedans in rows of ten lanes 4 m apart, 15 m between rows (JSON text).
std::string cruisingCarsScene(std::size_t cars, double duration_s, double physics_hz, bool skip_when_idle);

/// Runs every (cars, threads) pair, in that order.
std::vector<CarsBenchRow> runCarsBench(const CarsBenchOptions& options);

/// Writes DIR/cars.csv, DIR/cars.md and DIR/cars.png (gnuplot, with its script DIR/cars.gp and data
/// DIR/cars.dat). Throws std::runtime_error when a file cannot be written.
void writeCarsBenchReport(const CarsBenchOptions& options, const std::vector<CarsBenchRow>& rows);

}  // namespace sandbox
