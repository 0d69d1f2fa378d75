#include "sweep/custom_sweep.hpp"

#include "build_version.hpp"
#include "table_output.hpp"

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>

namespace sandbox {
namespace {

struct Varied {
  std::string key;
  std::vector<std::string> values;
};

Varied parseVary(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw deform::InputError("--vary: '" + text + "': expected key=v1,v2,...");
  Varied v{text.substr(0, eq), {}};
  std::string rest = text.substr(eq + 1);
  std::size_t from = 0;
  while (true) {
    const auto comma = rest.find(',', from);
    const std::string value =
        rest.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
    if (value.empty()) throw deform::InputError("--vary: '" + text + "': an empty value");
    v.values.push_back(value);
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  return v;
}

// The crash measure's columns, in the order of the table.
const std::vector<std::string>& measuredColumns() {
  static const std::vector<std::string> columns = {
      "impact_speed_mps", "residual_crush_m", "max_residual_crush_m", "max_dynamic_crush_m",
      "max_dent_m",       "restitution",      "plastic_work_J",       "kinetic_initial_J"};
  return columns;
}

}  // namespace

SweepPlan planCustom(const CustomSweepOptions& options) {
  if (options.scenes.empty()) throw deform::InputError("--scene: at least one scene");
  if (options.vary.empty()) throw deform::InputError("--vary: at least one key=v1,v2,...");
  std::vector<Varied> grid;
  for (const std::string& text : options.vary) grid.push_back(parseVary(text));
  for (std::size_t a = 0; a < grid.size(); ++a)
    for (std::size_t b = a + 1; b < grid.size(); ++b)
      if (grid[a].key == grid[b].key) throw deform::InputError("--vary: '" + grid[a].key + "' twice");
  SweepPlan plan;
  plan.kind = "custom";
  plan.version = buildVersion();
  nlohmann::json keys = nlohmann::json::array();
  for (const Varied& v : grid) keys.push_back(v.key);
  plan.options = {{"scenes", options.scenes}, {"vary", options.vary}, {"sets", options.sets}, {"keys", keys}};
  for (const std::string& scene : options.scenes) {
    std::vector<std::size_t> at(grid.size(), 0);  // an odometer over the grid, the last key fastest
    while (true) {
      std::vector<std::string> overrides = options.sets;
      nlohmann::json values = nlohmann::json::object();
      for (std::size_t k = 0; k < grid.size(); ++k) {
        overrides.push_back(grid[k].key + "=" + grid[k].values[at[k]]);
        values[grid[k].key] = grid[k].values[at[k]];
      }
      std::vector<scenes::Override> parsed;
      for (const std::string& o : overrides) parsed.push_back(scenes::parseOverride(o));
      scenes::loadScene(scene, parsed);  // refuses a bad key or value now, naming it
      addCase(plan, scene, overrides, "crash", {{"values", values}});
      std::size_t k = grid.size();
      while (k > 0 && ++at[k - 1] == grid[k - 1].values.size()) at[--k] = 0;
      if (k == 0) break;
    }
  }
  return plan;
}

void writeCustomReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                       const std::string& dir) {
  const std::vector<std::string> keys = plan.options.value("keys", std::vector<std::string>{});
  std::vector<std::string> columns = {"case", "scene"};
  columns.insert(columns.end(), keys.begin(), keys.end());
  columns.insert(columns.end(), measuredColumns().begin(), measuredColumns().end());
  columns.insert(columns.end(), {"diverged", "state_hash", "physics_ms", "deform_ms"});
  CsvTable csv(columns);
  std::ostringstream md;
  md << "|";
  for (const std::string& c : columns) md << " " << c << " |";
  md << "\n|";
  for (std::size_t i = 0; i < columns.size(); ++i) md << "---|";
  md << "\n";
  for (std::size_t i = 0; i < plan.cases.size(); ++i) {
    const SweepCase& c = plan.cases[i];
    const nlohmann::json& m = measured[i];
    const std::string what = "case " + c.id + ": measured.";
    const auto number = [&](const std::string& name) {
      if (!m.contains(name) || !m[name].is_number()) throw deform::InputError(what + name + ": not a number");
      return CsvTable::number(m[name].get<double>());
    };
    std::vector<std::string> cells = {c.id, m.value("scene_name", c.scene)};
    const auto values = c.labels.find("values");
    for (const std::string& key : keys) {
      const bool known = values != c.labels.end() && values->is_object() && values->contains(key) &&
                         (*values)[key].is_string();
      if (!known) throw deform::InputError("case " + c.id + ": labels.values." + key + ": missing");
      cells.push_back((*values)[key].get<std::string>());
    }
    for (const std::string& name : measuredColumns()) cells.push_back(number(name));
    cells.push_back(m.value("diverged", false) ? "1" : "0");
    cells.push_back(m.value("state_hash", ""));
    cells.push_back(number("physics_ms"));
    cells.push_back(number("deform_ms"));
    csv.addRow(cells);
    md << "|";
    for (const std::string& cell : cells) md << " " << cell << " |";
    md << "\n";
  }
  std::filesystem::create_directories(dir);
  scenes::writeFileAtomically(dir + "/sweep.csv", csv.text());
  scenes::writeFileAtomically(dir + "/sweep.md", md.str());
  std::printf("wrote %s/sweep.csv, %s/sweep.md\n", dir.c_str(), dir.c_str());
}

}  // namespace sandbox
