// `sandbox stress`: the stability table (stress/stress_suite.hpp) printed and written as CSV and Markdown.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "commands.hpp"
#include "stress/stress_suite.hpp"
#include "table_output.hpp"

#include <deform/error.hpp>
#include <scenes/scene_run.hpp>

namespace sandbox {
namespace {

struct StressFlags {
  std::string out_dir = "out/stress";
  bool quick = false;
  std::vector<std::string> groups;
};

std::string markdownTable(const std::vector<StressCase>& cases, bool quick) {
  std::ostringstream md;
  md << "| group | case | checks | result | measured | s |\n|---|---|---|---|---|---|\n";
  for (const StressCase& c : cases) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f", c.seconds);
    md << "| " << c.group << " | " << c.name << " | " << c.checks << " | " << (c.passed ? "pass" : "**FAIL**")
       << " | " << c.detail << " | " << seconds << " |\n";
  }
  md << "\n"
     << (quick ? "`--quick`: the ends of each range. " : "") << "Made by `build/bin/sandbox stress"
     << (quick ? " --quick" : "") << "`.\n";
  return md.str();
}

void runStress(const StressFlags& flags) {
  const std::vector<std::string> known = stressGroups();
  for (const std::string& g : flags.groups) {
    if (std::find(known.begin(), known.end(), g) == known.end()) {
      std::string names;
      for (const std::string& k : known) names += (names.empty() ? "" : ", ") + k;
      throw deform::InputError("--group: unknown group '" + g + "' (groups: " + names + ")");
    }
  }
  const std::vector<std::string> groups = flags.groups.empty() ? known : flags.groups;
  std::filesystem::create_directories(flags.out_dir);
  std::vector<StressCase> cases;
  int failed = 0;
  for (const std::string& group : groups) {
    for (StressCase& c : runStressGroup(group, flags.quick)) {
      std::printf("%-4s %-16s %-52s %6.2f s  %s\n", c.passed ? "ok" : "FAIL", c.group.c_str(), c.name.c_str(),
                  c.seconds, c.detail.c_str());
      std::fflush(stdout);
      failed += c.passed ? 0 : 1;
      cases.push_back(std::move(c));
    }
  }
  CsvTable csv({"group", "case", "checks", "passed", "detail", "seconds"});
  for (const StressCase& c : cases) {
    csv.addRow({c.group, c.name, c.checks, c.passed ? "1" : "0", c.detail, CsvTable::number(c.seconds)});
  }
  const std::string csv_path = flags.out_dir + "/stress.csv";
  const std::string md_path = flags.out_dir + "/stress.md";
  scenes::writeFileAtomically(csv_path, csv.text());
  scenes::writeFileAtomically(md_path, markdownTable(cases, flags.quick));
  std::printf("%zu cases, %d failed; wrote %s, %s\n", cases.size(), failed, csv_path.c_str(),
              md_path.c_str());
  if (failed > 0)
    throw std::runtime_error(std::to_string(failed) + " stress case(s) failed (see " + md_path + ")");
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
