// `sandbox bench grid`: vertices against control points (grid/bench_grid.hpp) as CSV and a log-log plot of
// the per-frame cost, one line per control-point count, the baselines beside them; its sweep
// (grid/grid_sweep.hpp) planned, run and merged in this process.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "grid/grid_sweep.hpp"
#include "sweep/sweep_case.hpp"

namespace sandbox {
namespace {

struct GridFlags {
  std::string out_dir = "out/grid";
  bool quick = false;
  unsigned threads = 0;
};

void runGrid(const GridFlags& flags) {
  const SweepPlan plan = planGrid(flags.quick, flags.threads);
  std::vector<nlohmann::json> measured;
  for (const SweepCase& c : plan.cases) measured.push_back(measureCase(c));
  writeGridReport(plan, measured, flags.out_dir);
}

}  // namespace

void registerBenchGridCommand(CLI::App& bench) {
  auto flags = std::make_shared<GridFlags>();
  auto* cmd = bench.add_subcommand("grid", "Render-mesh vertices against control points, with the baselines");
  cmd->add_option("--out", flags->out_dir, "Folder for grid.csv and grid.png")->capture_default_str();
  cmd->add_flag("--quick", flags->quick, "10k and 100k vertices, 8, 60 and 1000 points (under 2 min)");
  cmd->add_option("--threads", flags->threads, "Threads of the embedding pass (0 = all cores)")
      ->capture_default_str();
  cmd->callback([flags] { runGrid(*flags); });
}

}  // namespace sandbox
