// `sandbox bench cars` (cars_bench/cars_bench.hpp): many cars at 60 Hz on one and two threads.
#include <deform/error.hpp>

#include <memory>

#include <CLI/CLI.hpp>
#include "cars_bench/cars_bench.hpp"

#include "commands.hpp"

namespace sandbox {

void registerBenchCarsCommand(CLI::App& bench) {
  auto options = std::make_shared<CarsBenchOptions>();
  auto quick = std::make_shared<bool>(false);
  auto* cmd = bench.add_subcommand(
      "cars", "Many sedans cruising at 60 Hz: set-up, cost per simulated second by stage, 1 and 2 threads");
  cmd->add_option("--out", options->out_dir, "Folder for cars.csv, cars.md and cars.png")
      ->capture_default_str();
  cmd->add_flag("--quick", *quick, "The same car counts for 1 simulated second (well under a minute)");
  cmd->add_flag(
      "--skip-when-idle,!--no-skip-when-idle", options->skip_when_idle,
      "Cars skip their deformation step while nothing is near (vehicle.deformation.skip_when_idle, "
      "on by default; --no-skip-when-idle: a body wakes on its chassis's loads, the behaviour before "
      "issue 42)");
  cmd->add_option("--cars", options->cars, "Car counts to run, e.g. --cars 100 or --cars 10,100")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--threads", options->threads, "Thread counts to run each car count on, e.g. --threads 2")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--duration", options->duration_s, "Simulated seconds per run")->capture_default_str();
  cmd->add_option(
      "--budget-ms", options->budget_ms,
      "Deformation budget per physics step, every car together (the scenes' deformation_budget_ms): "
      "a level per car, and its estimate and measured time in the report");
  cmd->callback([options, quick] {
    if (!(options->duration_s > 0 && options->duration_s <= 1e4))
      throw deform::InputError("--duration: must be in (0, 10000] s");
    if (options->cars.empty() || options->threads.empty())
      throw deform::InputError("--cars, --threads: at least one each");
    for (const std::size_t cars : options->cars)
      if (cars < 1 || cars > 10000) throw deform::InputError("--cars: each count must be in [1, 10000]");
    for (const int threads : options->threads)
      if (threads < 1 || threads > 256) throw deform::InputError("--threads: each count must be in [1, 256]");
    if (options->budget_ms && !(*options->budget_ms >= 0))
      throw deform::InputError("--budget-ms: must be >= 0");
    CarsBenchOptions run = *options;
    if (*quick) run.duration_s = 1.0;  // every count: 200 cars cost about 1 s since the grid broad phase
    writeCarsBenchReport(run, runCarsBench(run));
  });
}

}  // namespace sandbox
