#include "stress/stress_sweep.hpp"

#include "build_version.hpp"
#include "commands.hpp"
#include "table_output.hpp"

#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace sandbox {
namespace {

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

}  // namespace

SweepPlan planStress(const std::vector<std::string>& groups, bool quick) {
  const std::vector<std::string> known = stressGroups();
  for (const std::string& g : groups) {
    if (std::find(known.begin(), known.end(), g) == known.end()) {
      std::string names;
      for (const std::string& k : known) names += (names.empty() ? "" : ", ") + k;
      throw deform::InputError("--group: unknown group '" + g + "' (groups: " + names + ")");
    }
  }
  SweepPlan plan;
  plan.kind = "stress";
  plan.version = buildVersion();
  plan.options = {{"quick", quick}, {"groups", groups}};
  for (const std::string& group : groups.empty() ? known : groups)
    addCase(plan, "", {}, "stress", {{"group", group}, {"quick", quick}});
  return plan;
}

nlohmann::json measureStressGroup(const std::string& group, bool quick) {
  nlohmann::json cases = nlohmann::json::array();
  for (const StressCase& c : runStressGroup(group, quick)) {
    cases.push_back({{"group", c.group},
                     {"name", c.name},
                     {"checks", c.checks},
                     {"passed", c.passed},
                     {"detail", c.detail},
                     {"seconds", c.seconds}});
  }
  return {{"cases", cases}};
}

std::vector<StressCase> stressCasesOf(const nlohmann::json& measured, const std::string& what) {
  if (!measured.is_object() || !measured.contains("cases") || !measured["cases"].is_array())
    throw deform::InputError(what + ": measured.cases: missing or not an array");
  std::vector<StressCase> cases;
  try {
    for (const nlohmann::json& j : measured["cases"]) {
      StressCase c{j.at("group").get<std::string>(), j.at("name").get<std::string>(),
                   j.at("checks").get<std::string>()};
      c.passed = j.at("passed").get<bool>();
      c.detail = j.at("detail").get<std::string>();
      c.seconds = j.at("seconds").get<double>();
      cases.push_back(std::move(c));
    }
  } catch (const nlohmann::json::exception& e) {
    throw deform::InputError(what + ": measured.cases: " + e.what());
  }
  return cases;
}

int writeStressReport(const std::vector<StressCase>& cases, bool quick, const std::string& dir) {
  int failed = 0;
  for (const StressCase& c : cases) {
    std::printf("%-4s %-16s %-52s %6.2f s  %s\n", c.passed ? "ok" : "FAIL", c.group.c_str(), c.name.c_str(),
                c.seconds, c.detail.c_str());
    failed += c.passed ? 0 : 1;
  }
  CsvTable csv({"group", "case", "checks", "passed", "detail", "seconds"});
  for (const StressCase& c : cases) {
    csv.addRow({c.group, c.name, c.checks, c.passed ? "1" : "0", c.detail, CsvTable::number(c.seconds)});
  }
  std::filesystem::create_directories(dir);
  const std::string csv_path = dir + "/stress.csv";
  const std::string md_path = dir + "/stress.md";
  scenes::writeFileAtomically(csv_path, csv.text());
  scenes::writeFileAtomically(md_path, markdownTable(cases, quick));
  std::printf("%zu cases, %d failed; wrote %s, %s\n", cases.size(), failed, csv_path.c_str(),
              md_path.c_str());
  std::fflush(stdout);
  return failed;
}

void writeStressSweepReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                            const std::string& dir) {
  std::vector<StressCase> cases;
  for (std::size_t i = 0; i < plan.cases.size(); ++i) {
    for (StressCase& c : stressCasesOf(measured[i], "case " + plan.cases[i].id))
      cases.push_back(std::move(c));
  }
  const int failed = writeStressReport(cases, plan.options.value("quick", false), dir);
  if (failed > 0)
    throw CommandFailure(std::to_string(failed) + " stress case(s) failed (see " + dir + "/stress.md)");
}

}  // namespace sandbox
