// `sandbox sweep plan|run|merge`: a sweep (sweep/) written as a plan, run in shards by any number of
// processes or machines, and merged into the tables the one-process command writes (README, "Sweeps").
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "converge/converge.hpp"
#include "grid/grid_sweep.hpp"
#include "stress/stress_sweep.hpp"
#include "sweep/custom_sweep.hpp"
#include "sweep/sweep_plan.hpp"
#include "sweep/sweep_run.hpp"
#include "tradeoff/tradeoff.hpp"

#include <deform/error.hpp>
#include <deform/path_checks.hpp>

namespace sandbox {
namespace {

struct PlanFlags {
  std::string out;
  TradeoffOptions tradeoff;
  std::vector<std::string> tradeoff_scenes;
  CustomSweepOptions custom;
  ConvergeOptions converge;
  std::vector<std::string> stress_groups;
  bool stress_quick = false;
  bool grid_quick = false;
  unsigned grid_threads = 0;
};

struct RunFlags {
  std::string plan;
  std::string shard = "1/1";
  std::string out_dir;
  bool strict = false;
  bool retry_failed = false;
};

struct MergeFlags {
  std::string dir;
  std::string out_dir;
};

// The plan checked whole before anything is written, then written atomically.
void writePlan(const SweepPlan& plan, const std::string& out) {
  const std::filesystem::path parent = std::filesystem::absolute(out).parent_path();
  if (!deform::isDirectory(parent)) throw deform::InputError("--out: no folder " + parent.string());
  writeAtomically(out, planText(plan));
  std::printf("wrote %s: %zu cases of a %s sweep\n", out.c_str(), plan.cases.size(), plan.kind.c_str());
}

void addPlanOut(CLI::App* cmd, PlanFlags& flags) {
  cmd->add_option("--out", flags.out, "The plan file to write (JSON Lines)")->required();
}

void registerPlan(CLI::App& sweep) {
  auto flags = std::make_shared<PlanFlags>();
  auto* plan = sweep.add_subcommand("plan", "Write a sweep's plan: one JSON line per independent case");
  plan->require_subcommand(1);

  auto* tradeoff = plan->add_subcommand("tradeoff", "The trade-off study (sandbox tradeoff's options)");
  tradeoff->add_option("--scene", flags->tradeoff_scenes,
                       "Scene to sweep (repeatable; default wall_crash and post_bumps)");
  tradeoff->add_flag("--quick", flags->tradeoff.quick, "Two values per knob and a lighter reference");
  tradeoff->add_option("--set", flags->tradeoff.sets, "Override a scene key in every run (repeatable)")
      ->expected(1)
      ->take_all();
  addPlanOut(tradeoff, *flags);
  tradeoff->callback([flags] {
    if (!flags->tradeoff_scenes.empty()) flags->tradeoff.scenes = flags->tradeoff_scenes;
    writePlan(planTradeoff(flags->tradeoff), flags->out);
  });

  auto* converge = plan->add_subcommand("converge", "The convergence study (sandbox converge's options)");
  converge->add_flag("--quick", flags->converge.quick, "60 and 250 points only");
  converge->add_option("--set", flags->converge.sets, "Override a scene key in every run (repeatable)")
      ->expected(1)
      ->take_all();
  addPlanOut(converge, *flags);
  converge->callback([flags] { writePlan(planConverge(flags->converge), flags->out); });

  auto* stress =
      plan->add_subcommand("stress", "The stress suite, one case per group (sandbox stress's options)");
  stress->add_flag("--quick", flags->stress_quick, "The ends of each range only");
  stress->add_option("--group", flags->stress_groups, "Only these groups (repeatable)");
  addPlanOut(stress, *flags);
  stress->callback([flags] { writePlan(planStress(flags->stress_groups, flags->stress_quick), flags->out); });

  auto* grid =
      plan->add_subcommand("grid", "The benchmark grid, one case per resolution (bench grid's options)");
  grid->add_flag("--quick", flags->grid_quick, "10k and 100k vertices, 8, 60 and 1000 points");
  grid->add_option("--threads", flags->grid_threads, "Threads of the embedding pass (0 = all cores)");
  addPlanOut(grid, *flags);
  grid->callback([flags] { writePlan(planGrid(flags->grid_quick, flags->grid_threads), flags->out); });

  auto* custom = plan->add_subcommand("custom", "Scenes crossed with a grid of scene keys, crash measured");
  custom->add_option("--scene", flags->custom.scenes, "Scene to sweep (repeatable)")->required();
  custom
      ->add_option("--vary", flags->custom.vary,
                   "A scene key and its values: --vary vehicle.start.speed_kmh=30,56 (repeatable: every "
                   "combination)")
      ->required()
      ->expected(1)
      ->take_all();
  custom->add_option("--set", flags->custom.sets, "Override a scene key in every run (repeatable)")
      ->expected(1)
      ->take_all();
  addPlanOut(custom, *flags);
  custom->callback([flags] { writePlan(planCustom(flags->custom), flags->out); });
}

void registerRun(CLI::App& sweep) {
  auto flags = std::make_shared<RunFlags>();
  auto* run = sweep.add_subcommand(
      "run", "Run one shard of a plan: one result file per case, skipping those already done");
  run->add_option("PLAN", flags->plan, "The plan file (sandbox sweep plan)")->required();
  run->add_option("--shard", flags->shard, "I/N: the I-th of N shards (cases I-1, I-1+N, ...)")
      ->capture_default_str();
  run->add_option("--out", flags->out_dir, "Folder for the results (shared by every shard)")->required();
  run->add_flag("--strict", flags->strict, "Refuse a plan made by another build or with changed scene files");
  run->add_flag("--retry-failed", flags->retry_failed, "Run again the cases whose result is a failure");
  run->callback([flags] {
    SweepRunOptions options;
    options.shard = parseShard(flags->shard);
    options.out_dir = flags->out_dir;
    options.strict = flags->strict;
    options.retry_failed = flags->retry_failed;
    const ShardSummary summary = runSweepShard(flags->plan, options);
    if (summary.failed > 0) {
      throw CommandFailure(std::to_string(summary.failed) + " case(s) of shard " + flags->shard +
                           " failed; each result records its error and exit code");
    }
  });
}

void registerMerge(CLI::App& sweep) {
  auto flags = std::make_shared<MergeFlags>();
  auto* merge = sweep.add_subcommand(
      "merge", "Gather a run folder into the one-process command's CSV, Markdown and plots");
  merge->add_option("DIR", flags->dir, "The folder of sandbox sweep run --out")->required();
  merge->add_option("--out", flags->out_dir, "Folder for the tables and plots")->required();
  merge->callback([flags] { mergeSweep(flags->dir, flags->out_dir); });
}

}  // namespace

void registerSweepCommand(CLI::App& app) {
  auto* sweep = app.add_subcommand("sweep", "Sweeps in shards: plan, run (any number of processes), merge");
  sweep->require_subcommand(1);
  registerPlan(*sweep);
  registerRun(*sweep);
  registerMerge(*sweep);
}

}  // namespace sandbox
