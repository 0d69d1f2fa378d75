// `sandbox converge`: the crush against the level of detail (DESIGN.md section 6: the reference is only a
// reference because the model converges there). The 56 km/h wall crash and the 32 km/h side pole at
// N = 60 .. 2000 control points; converge.csv, converge.md and a plot of residual crush against N.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "plot.hpp"
#include "table_output.hpp"

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

namespace sandbox {
namespace {

struct ConvergeFlags {
  std::string out_dir = "out/converge";
  bool quick = false;
  std::vector<std::string> sets;  ///< scene overrides for every run (the level of detail is set last)
};

/// One scene at one level of detail.
struct ConvergeRow {
  std::string scene;
  std::size_t control_points = 0;
  double residual_crush_m = 0, max_residual_crush_m = 0, max_dynamic_crush_m = 0, max_dent_m = 0;
  double restitution = 0, plastic_work_J = 0, kinetic_initial_J = 0, deform_ms = 0;
  double change_from_finest = 0;  ///< residual crush relative to the finest level's, minus one [1]
};

ConvergeRow runOne(const std::string& scene, std::size_t n, const std::vector<std::string>& sets) {
  std::vector<scenes::Override> overrides;
  for (const std::string& set : sets) overrides.push_back(scenes::parseOverride(set));
  overrides.push_back(scenes::parseOverride("vehicle.deformation.control_points=" + std::to_string(n)));
  scenes::SceneRun run(scenes::loadScene(scene, overrides));
  run.runToEnd();
  const vehicle::CrashMetrics m = run.simulation().metrics(run.carId(0));
  ConvergeRow row;
  row.scene = scene;
  row.control_points = n;
  row.residual_crush_m = m.residual_crush_m;
  row.max_residual_crush_m = m.max_residual_crush_m;
  row.max_dynamic_crush_m = m.max_dynamic_crush_m;
  row.max_dent_m = m.max_dent_m;
  row.restitution = m.restitution;
  row.plastic_work_J = m.energy.plastic_work_J;
  row.kinetic_initial_J = m.energy.kinetic_initial_J;
  row.deform_ms = run.times().deform_ms;
  return row;
}

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

void writeOutputs(const std::vector<ConvergeRow>& rows, const std::vector<std::string>& names,
                  const std::string& dir) {
  CsvTable csv({"scene", "control_points", "residual_crush_m", "max_residual_crush_m", "max_dynamic_crush_m",
                "max_dent_m", "restitution", "plastic_work_J", "kinetic_initial_J", "change_from_finest",
                "deform_ms"});
  std::ostringstream md;
  md << "Residual crush (six-station average) against the level of detail; the change is against the finest "
        "level.\n";
  for (const std::string& name : names) {
    md << "\n### " << name << "\n\n| control points | residual crush m | largest m | dynamic crush m "
       << "| deepest dent m | restitution | plastic / impact energy | change from finest | deform ms |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    for (const ConvergeRow& r : rows) {
      if (r.scene != name) continue;
      csv.addRow({r.scene, std::to_string(r.control_points), CsvTable::number(r.residual_crush_m),
                  CsvTable::number(r.max_residual_crush_m), CsvTable::number(r.max_dynamic_crush_m),
                  CsvTable::number(r.max_dent_m), CsvTable::number(r.restitution),
                  CsvTable::number(r.plastic_work_J), CsvTable::number(r.kinetic_initial_J),
                  CsvTable::number(r.change_from_finest), CsvTable::number(r.deform_ms)});
      md << "| " << r.control_points << " | " << fixed(r.residual_crush_m, 3) << " | "
         << fixed(r.max_residual_crush_m, 3) << " | " << fixed(r.max_dynamic_crush_m, 3) << " | "
         << fixed(r.max_dent_m, 3) << " | " << fixed(r.restitution, 3) << " | "
         << fixed(100 * r.plastic_work_J / std::max(r.kinetic_initial_J, 1e-9), 0) << " % | "
         << (r.change_from_finest >= 0 ? "+" : "") << fixed(100 * r.change_from_finest, 1) << " % | "
         << fixed(r.deform_ms, 0) << " |\n";
    }
  }
  scenes::writeFileAtomically(dir + "/converge.csv", csv.text());
  scenes::writeFileAtomically(dir + "/converge.md", md.str());
  std::printf("wrote %s/converge.csv, %s/converge.md\n", dir.c_str(), dir.c_str());

  // Residual crush and deepest dent against N (log axis), one line each per scene.
  std::ostringstream gp;
  const std::string base = dir + "/converge";
  gp << "set terminal pngcairo size 1100,700 font 'DejaVu Sans,11' noenhanced\n"
     << "set output " << gnuplotQuoted(base + ".png") << "\n"
     << "set title 'Crush against the level of detail (built-in sedan)'\n"
     << "set logscale x\nset grid\nset key top left box opaque\nset xrange [40:3000]\nset yrange [0:0.9]\n"
     << "set xlabel 'control points N'\nset ylabel 'crush [m]'\nset datafile separator ','\n"
     << "plot ";
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string data = base + "_" + names[k] + ".csv";
    std::ostringstream points;
    for (const ConvergeRow& r : rows)
      if (r.scene == names[k])
        points << r.control_points << "," << r.residual_crush_m << "," << r.max_dent_m << "\n";
    scenes::writeFileAtomically(data, points.str());
    const std::string colour = colours[k % 4];
    gp << (k ? ", \\\n  " : "") << gnuplotQuoted(data) << " using 1:2 with linespoints lw 2 pt 7 lc rgb '"
       << colour << "' title " << gnuplotQuoted(names[k] + ": residual crush (6 stations)") << ", \\\n  "
       << gnuplotQuoted(data) << " using 1:3 with linespoints lw 1 dt 2 pt 6 lc rgb '" << colour << "' title "
       << gnuplotQuoted(names[k] + ": deepest dent");
  }
  gp << "\n";
  if (runGnuplot(base + ".gp", gp.str())) std::printf("wrote %s.png\n", base.c_str());
}

void runConvergeCommand(const ConvergeFlags& flags) {
  const std::vector<std::string> names = {"wall_crash", "pole_side"};
  const std::vector<std::size_t> levels = flags.quick
                                              ? std::vector<std::size_t>{60, 250}
                                              : std::vector<std::size_t>{60, 120, 250, 500, 1000, 2000};
  std::filesystem::create_directories(flags.out_dir);
  std::vector<ConvergeRow> rows;
  for (const std::string& name : names) {
    const std::size_t first = rows.size();
    for (std::size_t n : levels) {
      rows.push_back(runOne(name, n, flags.sets));
      std::printf("%s, %zu points: residual crush %.3f m\n", name.c_str(), n, rows.back().residual_crush_m);
      std::fflush(stdout);
    }
    const double finest = rows.back().residual_crush_m;
    for (std::size_t i = first; i < rows.size(); ++i)
      rows[i].change_from_finest = finest > 0 ? rows[i].residual_crush_m / finest - 1.0 : 0.0;
  }
  writeOutputs(rows, names, flags.out_dir);
}

}  // namespace

void registerConvergeCommand(CLI::App& app) {
  auto flags = std::make_shared<ConvergeFlags>();
  auto* cmd = app.add_subcommand(
      "converge", "Crush against the level of detail: the wall crash and the side pole at 60 to 2000 points");
  cmd->add_option("--out", flags->out_dir, "Folder for converge.csv, converge.md and converge.png")
      ->capture_default_str();
  cmd->add_flag("--quick", flags->quick, "60 and 250 points only (seconds)");
  cmd->add_option(
         "--set", flags->sets,
         "Override a scene key in every run: --set vehicle.deformation.yield_limited=true (repeatable)")
      ->expected(1)
      ->take_all();
  cmd->callback([flags] { runConvergeCommand(*flags); });
}

}  // namespace sandbox
