#pragma once
// Each command group registers its subcommands on the program's CLI11 app. CLI11 is declared here, not
// included: its header costs 6 s of compiler time in each translation unit (docs/BENCHMARKS.md, "Build
// time"), and the files that only throw CommandFailure need none of it.
#include <stdexcept>

namespace CLI {
class App;
}  // namespace CLI

namespace sandbox {

/// A command that ran but did not succeed (failed sweep cases): main prints its message, exit code 1.
class CommandFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void registerMeshCommands(CLI::App& app);
void registerBenchCommands(CLI::App& app);
/// `sandbox figures`, in cmd_figures.cpp.
void registerFiguresCommand(CLI::App& app);

/// `sandbox bench step` (deformation dynamics), in bench_step.cpp.
void registerBenchStepCommand(CLI::App& bench);
/// `sandbox bench memory` (bytes per control point and vertex, RSS of many cars), in bench_memory.cpp.
void registerBenchMemoryCommand(CLI::App& bench);
/// `sandbox bench grid` (vertices against control points), in cmd_bench_grid.cpp.
void registerBenchGridCommand(CLI::App& bench);
/// `sandbox bench cars` (many cars, 1 and 2 threads), in cmd_bench_cars.cpp.
void registerBenchCarsCommand(CLI::App& bench);
/// `sandbox bench render` (offscreen frames by stage), in bench_render.cpp.
void registerBenchRenderCommand(CLI::App& bench);
/// `sandbox mesh render` (offscreen picture of a mesh), in cmd_mesh_render.cpp.
void registerMeshRenderCommand(CLI::App& mesh);
/// `sandbox run` (play a scene: summary, timeline, frames, video), in cmd_run.cpp.
void registerRunCommand(CLI::App& app);
/// `sandbox stress` (stability at the extremes), in cmd_stress.cpp.
void registerStressCommand(CLI::App& app);
/// `sandbox tradeoff` (speed against accuracy), in cmd_tradeoff.cpp.
void registerTradeoffCommand(CLI::App& app);
/// `sandbox converge`: crush against the level of detail (cmd_converge.cpp).
void registerConvergeCommand(CLI::App& app);
/// `sandbox sweep plan|run|merge` (sweeps in shards), in cmd_sweep.cpp.
void registerSweepCommand(CLI::App& app);
/// `sandbox export` (the damaged car at a time as a mesh), in cmd_export.cpp.
void registerExportCommand(CLI::App& app);

}  // namespace sandbox
