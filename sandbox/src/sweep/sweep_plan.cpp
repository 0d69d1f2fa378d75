#include "sweep/sweep_plan.hpp"

#include <scenes/scene_file.hpp>
#include <vehicle/world.hpp>

#include <deform/error.hpp>
#include <deform/path_checks.hpp>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace sandbox {
namespace {

constexpr int kPlanFormat = 1;

std::string caseId(std::size_t index) {
  char text[32];
  std::snprintf(text, sizeof text, "%04zu", index);
  return text;
}

// Field `name` of a plan line as a string; InputError naming the file, line and field otherwise.
std::string stringField(const nlohmann::json& line, const char* name, const std::string& where) {
  const auto it = line.find(name);
  if (it == line.end() || !it->is_string())
    throw deform::InputError(where + ": field '" + name + "': must be a string");
  return it->get<std::string>();
}

SweepCase parseCase(const nlohmann::json& line, const std::string& where) {
  if (!line.is_object()) throw deform::InputError(where + ": a case must be a JSON object");
  SweepCase c;
  c.id = stringField(line, "case", where);
  c.scene = stringField(line, "scene", where);
  c.scene_hash = stringField(line, "scene_hash", where);
  c.measure = stringField(line, "measure", where);
  if (c.measure != "tradeoff" && c.measure != "crash" && c.measure != "stress" && c.measure != "grid") {
    throw deform::InputError(where + ": field 'measure': unknown measure '" + c.measure +
                             "' (tradeoff, crash, stress, grid)");
  }
  const auto overrides = line.find("overrides");
  if (overrides == line.end() || !overrides->is_array())
    throw deform::InputError(where + ": field 'overrides': must be an array of strings");
  for (const nlohmann::json& o : *overrides) {
    if (!o.is_string()) throw deform::InputError(where + ": field 'overrides': must be an array of strings");
    c.overrides.push_back(o.get<std::string>());
  }
  const auto labels = line.find("labels");
  if (labels == line.end() || !labels->is_object())
    throw deform::InputError(where + ": field 'labels': must be an object");
  c.labels = *labels;
  return c;
}

}  // namespace

Shard parseShard(const std::string& text) {
  const auto slash = text.find('/');
  const auto bad = [&](const std::string& why) {
    return deform::InputError("--shard: '" + text + "': " + why + " (I/N with 1 <= I <= N, as 2/4)");
  };
  if (slash == std::string::npos) throw bad("no '/'");
  Shard shard;
  try {
    std::size_t used_i = 0, used_n = 0;
    const std::string i = text.substr(0, slash), n = text.substr(slash + 1);
    shard.index = std::stoi(i, &used_i);
    shard.count = std::stoi(n, &used_n);
    if (used_i != i.size() || used_n != n.size()) throw bad("not whole numbers");
  } catch (const std::logic_error&) {
    throw bad("not whole numbers");
  }
  if (shard.count < 1 || shard.index < 1 || shard.index > shard.count) throw bad("out of range");
  return shard;
}

std::string planText(const SweepPlan& plan) {
  std::ostringstream out;
  const nlohmann::json header = {{"sweep_plan", kPlanFormat},
                                 {"kind", plan.kind},
                                 {"version", plan.version},
                                 {"options", plan.options},
                                 {"cases", plan.cases.size()}};
  out << header.dump() << "\n";
  for (const SweepCase& c : plan.cases) {
    const nlohmann::json line = {
        {"case", c.id},         {"scene", c.scene},  {"scene_hash", c.scene_hash}, {"overrides", c.overrides},
        {"measure", c.measure}, {"labels", c.labels}};
    out << line.dump() << "\n";
  }
  return out.str();
}

SweepPlan parsePlan(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  std::string line;
  std::size_t number = 0;
  SweepPlan plan;
  std::size_t declared = 0;
  std::set<std::string> ids;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = path + ":" + std::to_string(number);
    if (line.empty()) throw deform::InputError(where + ": empty line");
    nlohmann::json parsed;
    try {
      parsed = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error&) {
      throw deform::InputError(where + ": not a JSON line");
    }
    if (number == 1) {
      if (!parsed.is_object() || !parsed.contains("sweep_plan"))
        throw deform::InputError(where + ": field 'sweep_plan': missing (not a sweep plan)");
      if (parsed["sweep_plan"] != kPlanFormat)
        throw deform::InputError(where + ": field 'sweep_plan': format " + parsed["sweep_plan"].dump() +
                                 " is not 1");
      plan.kind = stringField(parsed, "kind", where);
      plan.version = stringField(parsed, "version", where);
      if (!parsed.contains("options") || !parsed["options"].is_object())
        throw deform::InputError(where + ": field 'options': must be an object");
      plan.options = parsed["options"];
      if (!parsed.contains("cases") || !parsed["cases"].is_number_unsigned())
        throw deform::InputError(where + ": field 'cases': must be a count");
      declared = parsed["cases"].get<std::size_t>();
      continue;
    }
    SweepCase c = parseCase(parsed, where);
    if (!ids.insert(c.id).second) throw deform::InputError(where + ": field 'case': '" + c.id + "' twice");
    plan.cases.push_back(std::move(c));
  }
  if (number == 0) throw deform::InputError(path + ": empty (not a sweep plan)");
  if (plan.cases.size() != declared) {
    throw deform::InputError(path + ": the header says " + std::to_string(declared) +
                             " cases, the file has " + std::to_string(plan.cases.size()) + " (truncated?)");
  }
  return plan;
}

std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || deform::isDirectory(path)) throw deform::InputError(path + ": cannot read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

SweepPlan readPlan(const std::string& path) {
  return parsePlan(readWholeFile(path), path);
}

std::string textHash(const std::string& text) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(vehicle::fnv1a(text.data(), text.size())));
  return hex;
}

std::string planSceneName(const std::string& name_or_path) {
  const std::string path = scenes::resolveScenePath(name_or_path);
  if (!deform::pathExists(name_or_path)) return name_or_path;  // a shipped scene's name
  return std::filesystem::absolute(path).lexically_normal().string();
}

std::string sceneFileHash(const std::string& name_or_path) {
  return textHash(readWholeFile(scenes::resolveScenePath(name_or_path)));
}

SweepCase& addCase(SweepPlan& plan, const std::string& scene, std::vector<std::string> overrides,
                   const std::string& measure, nlohmann::json labels) {
  SweepCase c;
  c.id = caseId(plan.cases.size());
  c.scene = scene.empty() ? scene : planSceneName(scene);  // empty: the measure makes its own scenes
  c.scene_hash = scene.empty() ? std::string() : sceneFileHash(scene);
  c.overrides = std::move(overrides);
  c.measure = measure;
  c.labels = std::move(labels);
  plan.cases.push_back(std::move(c));
  return plan.cases.back();
}

void writeAtomically(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    if (!out.flush()) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error(path + ": cannot write");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot write (" + ec.message() + ")");
}

}  // namespace sandbox
