// `sandbox converge`: the crush against the level of detail (converge/converge.hpp), its sweep run and
// merged in this process (`sandbox sweep plan converge` shares the same plan out).
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "converge/converge.hpp"
#include "sweep/sweep_case.hpp"

namespace sandbox {
namespace {

struct ConvergeFlags {
  std::string out_dir = "out/converge";
  ConvergeOptions options;
};

void runConvergeCommand(const ConvergeFlags& flags) {
  const SweepPlan plan = planConverge(flags.options);
  std::vector<nlohmann::json> measured;
  for (const SweepCase& c : plan.cases) measured.push_back(measureCase(c));
  writeConvergeReport(plan, measured, flags.out_dir);
}

}  // namespace

void registerConvergeCommand(CLI::App& app) {
  auto flags = std::make_shared<ConvergeFlags>();
  auto* cmd = app.add_subcommand(
      "converge", "Crush against the level of detail: the wall crash and the side pole at 60 to 2000 points");
  cmd->add_option("--out", flags->out_dir, "Folder for converge.csv, converge.md and converge.png")
      ->capture_default_str();
  cmd->add_flag("--quick", flags->options.quick, "60 and 250 points only (seconds)");
  cmd->add_option(
         "--set", flags->options.sets,
         "Override a scene key in every run: --set vehicle.deformation.yield_limited=true (repeatable)")
      ->expected(1)
      ->take_all();
  cmd->callback([flags] { runConvergeCommand(*flags); });
}

}  // namespace sandbox
