// `sandbox tradeoff`: the speed/accuracy sweep (tradeoff/tradeoff.hpp) as CSV, Markdown and Pareto plots.
#include <filesystem>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "tradeoff/skin_error_report.hpp"
#include "tradeoff/tradeoff.hpp"

namespace sandbox {
namespace {

struct TradeoffFlags {
  TradeoffOptions options;
  std::vector<std::string> scenes;
  std::string out_dir = "out/tradeoff";
  bool skin_only = false;  ///< the skin alone on known fields (tradeoff/skin_error.hpp), no physics
};

void runTradeoffCommand(TradeoffFlags& flags) {
  if (flags.skin_only) {
    std::filesystem::create_directories(flags.out_dir);
    const bool quick = flags.options.quick;
    const auto rows = runSkinError(quick ? SkinErrorOptions::quick() : SkinErrorOptions{});
    writeSkinErrorReport(rows, flags.out_dir,
                         std::string("sandbox tradeoff --skin-only") + (quick ? " --quick" : ""));
    return;
  }
  if (!flags.scenes.empty()) flags.options.scenes = flags.scenes;
  // The sweep's plan, every case run and merged in this process (sweep/: the same plan can be shared out).
  writeTradeoffReport(runTradeoff(flags.options), flags.out_dir);
}

}  // namespace

void registerTradeoffCommand(CLI::App& app) {
  auto flags = std::make_shared<TradeoffFlags>();
  auto* cmd =
      app.add_subcommand("tradeoff", "Speed against accuracy: every knob's cost and error, Pareto plots");
  cmd->add_option("--scene", flags->scenes, "Scene to sweep (repeatable; default wall_crash and post_bumps)");
  cmd->add_option("--out", flags->out_dir, "Folder for tradeoff.csv, tradeoff.md and the plots")
      ->capture_default_str();
  cmd->add_flag("--quick", flags->options.quick, "Two values per knob and a lighter reference (under 2 min)");
  cmd->add_option(
         "--set", flags->options.sets,
         "Override a scene key in every run, before the knob's own: --set duration_s=0.5 (repeatable)")
      ->expected(1)
      ->take_all();
  cmd->add_flag("--skin-only", flags->skin_only,
                "The skin alone: control points moved by known smooth fields (bend, twist, frontal crush, "
                "affine), the render mesh against the exact field for N, K, alpha and idw/mls; writes "
                "skin_error.csv, skin_error.md and plots");
  cmd->callback([flags] { runTradeoffCommand(*flags); });
}

}  // namespace sandbox
