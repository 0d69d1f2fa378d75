#include "sweep/sweep_run.hpp"

#include "build_version.hpp"
#include "commands.hpp"
#include "converge/converge.hpp"
#include "grid/grid_sweep.hpp"
#include "stress/stress_sweep.hpp"
#include "sweep/custom_sweep.hpp"
#include "sweep/sweep_case.hpp"
#include "tradeoff/tradeoff.hpp"

#include <deform/error.hpp>
#include <deform/path_checks.hpp>

#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

namespace fs = std::filesystem;

namespace sandbox {
namespace {

std::string casePath(const std::string& dir, const SweepCase& c) {
  return dir + "/cases/" + c.id + ".json";
}

// A result file read back, or null when it is not a whole JSON object.
nlohmann::json readResult(const std::string& path) {
  try {
    nlohmann::json result = nlohmann::json::parse(readWholeFile(path));
    if (result.is_object()) return result;
  } catch (const std::exception&) {
  }
  return nullptr;
}

// A result's text field, "" when it is missing or not text (a hand-edited or foreign file).
std::string field(const nlohmann::json& result, const char* name) {
  const auto it = result.find(name);
  return it != result.end() && it->is_string() ? it->get<std::string>() : std::string();
}

std::string describe(const SweepCase& c) {
  std::string text = c.id + " " + c.scene;
  for (const std::string& o : c.overrides) text += " " + o;
  return text;
}

// Another build, or scene files that changed since the plan was made: a warning, or (strict) refused.
void checkProvenance(const SweepPlan& plan, const std::string& plan_path, bool strict) {
  std::vector<std::string> problems;
  if (plan.version != buildVersion()) {
    problems.push_back(plan_path + ": made by build " + plan.version + ", this is " + buildVersion());
  }
  std::map<std::string, std::string> checked;
  for (const SweepCase& c : plan.cases) {
    if (c.scene.empty() || checked.count(c.scene)) continue;
    checked[c.scene] = c.scene_hash;
    const std::string now = sceneFileHash(c.scene);  // InputError naming a scene that is gone
    if (now != c.scene_hash) {
      problems.push_back(plan_path + ": scene " + c.scene + " has changed since the plan (hash " + now +
                         ", the plan's " + c.scene_hash + ")");
    }
  }
  for (const std::string& p : problems) {
    if (strict) throw deform::InputError(p + " (--strict)");
    std::fprintf(stderr, "sandbox: warning: %s\n", p.c_str());
  }
}

std::string joined(const std::vector<std::string>& names, std::size_t most) {
  std::string text;
  for (std::size_t i = 0; i < names.size() && i < most; ++i) text += (i ? ", " : "") + names[i];
  if (names.size() > most) text += ", ... (" + std::to_string(names.size()) + " in all)";
  return text;
}

}  // namespace

ShardSummary runSweepShard(const std::string& plan_path, const SweepRunOptions& options) {
  const std::string text = readWholeFile(plan_path);
  const SweepPlan plan = parsePlan(text, plan_path);
  const std::string plan_id = textHash(text);
  checkProvenance(plan, plan_path, options.strict);
  const std::string& dir = options.out_dir;
  if (deform::pathExists(dir) && !deform::isDirectory(dir))
    throw deform::InputError("--out: " + dir + " is not a folder");
  const std::string kept_plan = dir + "/plan.jsonl";
  if (deform::pathExists(kept_plan)) {
    if (readWholeFile(kept_plan) != text) {
      throw deform::InputError(kept_plan + ": this folder holds the results of another plan than " +
                               plan_path + " (use another --out)");
    }
  }
  std::error_code ec;
  fs::create_directories(dir + "/cases", ec);
  if (ec) throw deform::InputError("--out: cannot create " + dir + "/cases (" + ec.message() + ")");
  if (!deform::pathExists(kept_plan)) writeAtomically(kept_plan, text);

  ShardSummary summary;
  for (std::size_t i = 0; i < plan.cases.size(); ++i) {
    if (!options.shard.holds(i)) continue;
    const SweepCase& c = plan.cases[i];
    ++summary.cases;
    const std::string path = casePath(dir, c);
    if (deform::pathExists(path)) {
      const nlohmann::json kept = readResult(path);
      const bool ours = kept.is_object() && field(kept, "plan_id") == plan_id && field(kept, "case") == c.id;
      const bool failed = ours && field(kept, "status") != "done";
      if (ours && !(failed && options.retry_failed)) {
        ++summary.skipped;
        summary.failed += failed ? 1 : 0;
        continue;
      }
    }
    std::printf("case %s: running\n", describe(c).c_str());
    std::fflush(stdout);
    const nlohmann::json result = runCase(c, plan_id);
    writeAtomically(path, result.dump() + "\n");
    ++summary.ran;
    if (result["status"] != "done") {
      ++summary.failed;
      std::printf("case %s: FAILED (exit %d): %s\n", c.id.c_str(), result["exit_code"].get<int>(),
                  result["error"].get<std::string>().c_str());
    } else {
      std::printf("case %s: done in %.2f s\n", c.id.c_str(), result["seconds"].get<double>());
    }
    std::fflush(stdout);
  }
  std::printf("shard %d/%d of %s: %zu cases, %zu run, %zu already done, %zu failed; results in %s/cases\n",
              options.shard.index, options.shard.count, plan_path.c_str(), summary.cases, summary.ran,
              summary.skipped, summary.failed, dir.c_str());
  return summary;
}

MergedSweep gatherSweep(const std::string& dir) {
  if (!deform::isDirectory(dir)) throw deform::InputError(dir + ": no such folder");
  const std::string plan_path = dir + "/plan.jsonl";
  if (!deform::pathExists(plan_path))
    throw deform::InputError(plan_path + ": missing (not a folder of `sandbox sweep run`)");
  const std::string text = readWholeFile(plan_path);
  MergedSweep merged{parsePlan(text, plan_path), {}};
  const std::string plan_id = textHash(text);
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < merged.plan.cases.size(); ++i) index[merged.plan.cases[i].id] = i;

  std::vector<nlohmann::json> results(merged.plan.cases.size());
  std::vector<std::string> foreign;
  if (deform::isDirectory(dir + "/cases")) {
    std::set<std::string> names;  // sorted, so messages do not depend on the folder's order
    for (const fs::directory_entry& entry : fs::directory_iterator(dir + "/cases"))
      names.insert(entry.path().filename().string());
    for (const std::string& name : names) {
      if (name.find(".tmp.") != std::string::npos) continue;  // a write cut short: not a result
      const std::string id = name.size() > 5 && name.substr(name.size() - 5) == ".json"
                                 ? name.substr(0, name.size() - 5)
                                 : std::string();
      const auto it = index.find(id);
      if (it == index.end()) {
        foreign.push_back("cases/" + name + " (no case of the plan)");
        continue;
      }
      nlohmann::json result = readResult(dir + "/cases/" + name);
      if (!result.is_object()) {
        foreign.push_back("cases/" + name + " (not a result)");
      } else if (field(result, "plan_id") != plan_id || field(result, "case") != id) {
        foreign.push_back("cases/" + name + " (of another plan)");
      } else {
        results[it->second] = std::move(result);
      }
    }
  }
  std::vector<std::string> missing;
  for (std::size_t i = 0; i < results.size(); ++i)
    if (results[i].is_null()) missing.push_back(merged.plan.cases[i].id);
  if (!missing.empty() || !foreign.empty()) {
    // (appended piece by piece: gcc 12's -Wrestrict misfires on " " + std::to_string(...) here)
    std::string message = dir + ": refusing to merge:";
    if (!missing.empty()) {
      message.append(" ").append(std::to_string(missing.size())).append(" case(s) missing: ");
      message.append(joined(missing, 12)).append(";");
    }
    if (!foreign.empty()) {
      message.append(" ").append(std::to_string(foreign.size())).append(" foreign: ");
      message.append(joined(foreign, 6)).append(";");
    }
    message += " run the missing shards (sandbox sweep run), or use a clean folder";
    throw deform::InputError(message);
  }
  std::vector<std::string> failed;
  std::set<std::string> versions;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const nlohmann::json& r = results[i];
    versions.insert(field(r, "version"));
    if (field(r, "status") != "done") {
      failed.push_back(merged.plan.cases[i].id);
      std::fprintf(
          stderr, "sandbox: case %s (%s) failed, exit %d: %s\n", merged.plan.cases[i].id.c_str(),
          describe(merged.plan.cases[i]).c_str(),
          r.contains("exit_code") && r.at("exit_code").is_number_integer() ? r.at("exit_code").get<int>() : 1,
          field(r, "error").c_str());
    } else {
      merged.measured.push_back(r.contains("measured") ? r.at("measured") : nlohmann::json());
    }
  }
  if (!failed.empty()) {
    throw CommandFailure(std::to_string(failed.size()) + " case(s) of " + dir + " failed (" +
                         joined(failed, 12) + "); nothing merged. Run them again with sandbox sweep run " +
                         "--retry-failed once the cause is fixed");
  }
  if (versions.size() > 1) {
    std::fprintf(stderr, "sandbox: warning: %s: results made by %zu builds (%s)\n", dir.c_str(),
                 versions.size(),
                 joined(std::vector<std::string>(versions.begin(), versions.end()), 4).c_str());
  }
  return merged;
}

void writeSweepReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                      const std::string& out_dir) {
  if (plan.kind == "tradeoff") {
    writeTradeoffReport(assembleTradeoff(plan, measured), out_dir);
  } else if (plan.kind == "converge") {
    writeConvergeReport(plan, measured, out_dir);
  } else if (plan.kind == "grid") {
    writeGridReport(plan, measured, out_dir);
  } else if (plan.kind == "stress") {
    writeStressSweepReport(plan, measured, out_dir);
  } else if (plan.kind == "custom") {
    writeCustomReport(plan, measured, out_dir);
  } else {
    throw deform::InputError("plan kind '" + plan.kind + "': no merge for it in this build");
  }
}

void mergeSweep(const std::string& dir, const std::string& out_dir) {
  const MergedSweep merged = gatherSweep(dir);
  std::printf("%s: %zu cases of a %s plan, all done\n", dir.c_str(), merged.plan.cases.size(),
              merged.plan.kind.c_str());
  writeSweepReport(merged.plan, merged.measured, out_dir);
}

}  // namespace sandbox
