#include "grid/grid_sweep.hpp"

#include "build_version.hpp"
#include "grid/bench_grid.hpp"
#include "plot.hpp"
#include "table_output.hpp"

#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

namespace sandbox {
namespace {

GridOptions optionsOf(const nlohmann::json& labels) {
  GridOptions options = labels.value("quick", false) ? GridOptions::quick() : GridOptions{};
  options.threads = labels.value("threads", 0u);
  return options;
}

nlohmann::json rowJson(const GridRow& r) {
  return {{"method", r.method},           {"vertices", r.vertices}, {"control_points", r.control_points},
          {"constraints", r.constraints}, {"hull_ms", r.hull_ms},   {"lod_ms", r.lod_ms},
          {"body_ms", r.body_ms},         {"skin_ms", r.skin_ms},   {"skin_bytes", r.skin_bytes},
          {"step_ms", r.step_ms},         {"embed_ms", r.embed_ms}, {"note", r.note}};
}

GridRow rowOf(const nlohmann::json& j) {
  GridRow r;
  r.method = j.at("method").get<std::string>();
  r.vertices = j.at("vertices").get<std::size_t>();
  r.control_points = j.at("control_points").get<std::size_t>();
  r.constraints = j.at("constraints").get<std::size_t>();
  r.hull_ms = j.at("hull_ms").get<double>();
  r.lod_ms = j.at("lod_ms").get<double>();
  r.body_ms = j.at("body_ms").get<double>();
  r.skin_ms = j.at("skin_ms").get<double>();
  r.skin_bytes = j.at("skin_bytes").get<std::size_t>();
  r.step_ms = j.at("step_ms").get<double>();
  r.embed_ms = j.at("embed_ms").get<double>();
  r.note = j.at("note").get<std::string>();
  return r;
}

nlohmann::json crashJson(const baselines::SoftBodyCrash& c) {
  return {{"speed_kmh", c.speed_kmh},
          {"finite", c.finite},
          {"tunnelled", c.tunnelled},
          {"max_extent_growth", c.max_extent_growth},
          {"max_node_speed_mps", c.max_node_speed_mps},
          {"residual_dent_m", c.residual_dent_m},
          {"stable", c.stable},
          {"verdict", c.verdict}};
}

baselines::SoftBodyCrash crashOf(const nlohmann::json& j) {
  baselines::SoftBodyCrash c;
  c.speed_kmh = j.at("speed_kmh").get<double>();
  c.finite = j.at("finite").get<bool>();
  c.tunnelled = j.at("tunnelled").get<bool>();
  c.max_extent_growth = j.at("max_extent_growth").get<double>();
  c.max_node_speed_mps = j.at("max_node_speed_mps").get<double>();
  c.residual_dent_m = j.at("residual_dent_m").get<double>();
  c.stable = j.at("stable").get<bool>();
  c.verdict = j.at("verdict").get<std::string>();
  return c;
}

std::string csvText(const std::vector<GridRow>& rows) {
  CsvTable csv({"method", "vertices", "control_points", "constraints", "hull_ms", "lod_ms", "body_ms",
                "skin_ms", "build_ms", "skin_bytes", "step_ms", "embed_ms", "frame_ms", "note"});
  for (const GridRow& r : rows) {
    csv.addRow({r.method, std::to_string(r.vertices), std::to_string(r.control_points),
                std::to_string(r.constraints), CsvTable::number(r.hull_ms), CsvTable::number(r.lod_ms),
                CsvTable::number(r.body_ms), CsvTable::number(r.skin_ms),
                CsvTable::number(r.hull_ms + r.lod_ms + r.body_ms + r.skin_ms), std::to_string(r.skin_bytes),
                CsvTable::number(r.step_ms), CsvTable::number(r.embed_ms), CsvTable::number(r.frame_ms()),
                r.note});
  }
  return csv.text();
}

void printRow(const GridRow& r) {
  std::printf(
      "%-34s %8zu vertices %6zu points  build %8.1f ms (hull %.1f, lod %.1f, body %.1f, skin %.1f)  "
      "skin %7.1f MB  step %8.3f ms  embed %8.3f ms  frame %8.3f ms%s%s\n",
      r.method.c_str(), r.vertices, r.control_points, r.hull_ms + r.lod_ms + r.body_ms + r.skin_ms, r.hull_ms,
      r.lod_ms, r.body_ms, r.skin_ms, static_cast<double>(r.skin_bytes) / 1e6, r.step_ms, r.embed_ms,
      r.frame_ms(), r.note.empty() ? "" : "  ", r.note.c_str());
  std::fflush(stdout);
}

void plot(const std::vector<GridRow>& rows, const std::string& dir) {
  // One data block per line: the skin at each control-point count, then each baseline.
  std::map<std::string, std::ostringstream> series;
  std::vector<std::string> order;
  for (const GridRow& r : rows) {
    // Dense is in the table; Bullet on the control mesh has one resolution (its cost is the step's).
    if (r.method == "skin dense" || r.method == "Bullet soft body (control mesh)") continue;
    const std::string name = r.method == "skin K=8"
                                 ? "N = " + std::to_string(r.control_points) + " (step + embed, K = 8)"
                                 : r.method;
    if (!series.count(name)) order.push_back(name);
    series[name] << r.vertices << " " << std::max(r.frame_ms(), 1e-4) << "\n";
  }
  std::ostringstream data, gp;
  for (const std::string& name : order) data << "# " << name << "\n" << series[name].str() << "\n\n";
  scenes::writeFileAtomically(dir + "/grid.dat", data.str());
  gp << "set terminal pngcairo size 1200,760 font 'DejaVu Sans,11' noenhanced\n"
     << "set output " << gnuplotQuoted(dir + "/grid.png") << "\n"
     << "set title 'Per-frame cost against render-mesh vertices: the skin at each level of detail, and the "
        "baselines'\n"
     << "set logscale xy\nset grid\nset key top left font ',9'\n"
     << "set xlabel 'render-mesh vertices (builtin:sedan)'\n"
     << "set ylabel 'ms per 60 Hz frame (deformation step + embedding)'\n"
     << "plot ";
  for (std::size_t i = 0; i < order.size(); ++i) {
    const bool baseline = order[i].rfind("N = ", 0) != 0;
    gp << (i ? ", \\\n  " : "") << gnuplotQuoted(dir + "/grid.dat") << " index " << i
       << " using 1:2 with linespoints lw 2 pt " << (baseline ? 5 : 7) << (baseline ? " dt 2" : "")
       << " title " << gnuplotQuoted(order[i]);
  }
  gp << "\n";
  if (runGnuplot(dir + "/grid.gp", gp.str())) std::printf("wrote %s/grid.png\n", dir.c_str());
}

}  // namespace

SweepPlan planGrid(bool quick, unsigned threads) {
  const GridOptions options = quick ? GridOptions::quick() : GridOptions{};
  SweepPlan plan;
  plan.kind = "grid";
  plan.version = buildVersion();
  plan.options = {{"quick", quick}, {"threads", threads}};
  for (std::size_t i = 0; i < options.vertices.size(); ++i) {
    addCase(plan, "", {}, "grid",
            {{"part", "resolution"},
             {"vertices", options.vertices[i]},
             {"first", i == 0},
             {"quick", quick},
             {"threads", threads}});
  }
  for (double kmh : options.bullet_crash_speeds_kmh)
    addCase(plan, "", {}, "grid", {{"part", "bullet_crash"}, {"speed_kmh", kmh}});
  return plan;
}

nlohmann::json measureGridCase(const SweepCase& sweep_case) {
  const nlohmann::json& labels = sweep_case.labels;
  const std::string part = labels.value("part", "");
  if (part == "resolution") {
    std::map<std::size_t, double> step_ms_of;
    nlohmann::json rows = nlohmann::json::array();
    for (const GridRow& r :
         runBenchGridResolution(optionsOf(labels), labels.at("vertices").get<std::size_t>(),
                                labels.value("first", false), step_ms_of))
      rows.push_back(rowJson(r));
    return {{"rows", rows}};
  }
  if (part == "bullet_crash")
    return {{"crash", crashJson(bulletCrash(labels.at("speed_kmh").get<double>()))}};
  throw deform::InputError("case " + sweep_case.id + ": labels.part: '" + part +
                           "' is not a grid part (resolution, bullet_crash)");
}

void writeGridReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                     const std::string& dir) {
  std::vector<GridRow> rows;
  std::vector<baselines::SoftBodyCrash> crashes;
  for (std::size_t i = 0; i < plan.cases.size(); ++i) {
    try {
      if (measured[i].contains("rows")) {
        for (const nlohmann::json& j : measured[i].at("rows")) rows.push_back(rowOf(j));
      } else {
        crashes.push_back(crashOf(measured[i].at("crash")));
      }
    } catch (const nlohmann::json::exception& e) {
      throw deform::InputError("case " + plan.cases[i].id + ": measured: " + e.what());
    }
  }
  for (const GridRow& r : rows) printRow(r);
  std::filesystem::create_directories(dir);
  scenes::writeFileAtomically(dir + "/grid.csv", csvText(rows));
  std::printf("wrote %s/grid.csv\n", dir.c_str());
  CsvTable crash_table({"speed_kmh", "stable", "finite", "tunnelled", "max_extent_growth",
                        "max_node_speed_mps", "residual_dent_m", "verdict"});
  for (const baselines::SoftBodyCrash& c : crashes) {
    std::printf("Bullet soft body (60-point control mesh) in wall_crash at %g km/h: %s\n", c.speed_kmh,
                c.verdict.c_str());
    crash_table.addRow({CsvTable::number(c.speed_kmh), c.stable ? "1" : "0", c.finite ? "1" : "0",
                        c.tunnelled ? "1" : "0", CsvTable::number(c.max_extent_growth),
                        CsvTable::number(c.max_node_speed_mps), CsvTable::number(c.residual_dent_m),
                        c.verdict});
  }
  scenes::writeFileAtomically(dir + "/bullet_crash.csv", crash_table.text());
  plot(rows, dir);
}

}  // namespace sandbox
