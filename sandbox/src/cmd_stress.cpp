// `sandbox stress`: the stability table (stress/stress_suite.hpp), its sweep (stress/stress_sweep.hpp) run
// group by group and merged in this process, printed and written as CSV and Markdown.
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "stress/stress_sweep.hpp"

namespace sandbox {
namespace {

struct StressFlags {
  std::string out_dir = "out/stress";
  bool quick = false;
  std::vector<std::string> groups;
};

void runStress(const StressFlags& flags) {
  const SweepPlan plan = planStress(flags.groups, flags.quick);
  std::vector<nlohmann::json> measured;
  for (const SweepCase& c : plan.cases)
    measured.push_back(measureStressGroup(c.labels.at("group").get<std::string>(), flags.quick));
  writeStressSweepReport(plan, measured, flags.out_dir);
}

}  // namespace

void registerStressCommand(CLI::App& app) {
  auto flags = std::make_shared<StressFlags>();
  auto* cmd =
      app.add_subcommand("stress", "Stability at the extremes: every range to its ends, with a table");
  cmd->add_option("--out", flags->out_dir, "Folder for stress.csv and stress.md")->capture_default_str();
  cmd->add_flag("--quick", flags->quick, "The ends of each range only (under two minutes)");
  cmd->add_option("--group", flags->groups, "Only these groups (repeatable)");
  cmd->callback([flags] { runStress(*flags); });
}

}  // namespace sandbox
