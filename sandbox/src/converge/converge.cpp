#include "converge/converge.hpp"

#include "build_version.hpp"
#include "plot.hpp"
#include "sweep/sweep_case.hpp"
#include "table_output.hpp"

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace sandbox {
namespace {

/// One scene at one level of detail.
struct ConvergeRow {
  std::string scene;
  std::size_t control_points = 0;
  double residual_crush_m = 0, max_residual_crush_m = 0, max_dynamic_crush_m = 0, max_dent_m = 0;
  double restitution = 0, plastic_work_J = 0, kinetic_initial_J = 0, deform_ms = 0, crushed_volume_m3 = 0;
  /// The stations behind the residual crush, across the width (NaN: the station's line missed the
  /// surface), and their height [m]: where a level of detail gains or loses crush.
  std::vector<double> crush_profile_m;
  double crush_height_m = 0;
  /// The same six stations on the car's own surface (its render mesh, moved by its skin): NaN when the
  /// measurement predates it [m]; and that crush relative to the finest level's, minus one [1].
  double surface_crush_m = std::nan("");
  double surface_change_from_finest = 0;
  /// The obstacle's work on the body (summary.json energy.contact_work_J): NaN when the measurement
  /// predates it [J]; and that work relative to the finest level's, minus one [1].
  double contact_work_J = std::nan("");
  double contact_work_change_from_finest = 0;
  double change_from_finest = 0;         ///< residual crush relative to the finest level's, minus one [1]
  double volume_change_from_finest = 0;  ///< crushed volume relative to the finest level's, minus one [1]
};

ConvergeRow rowOf(const SweepCase& c, const nlohmann::json& m) {
  const auto number = [&](const char* name) { return measuredNumber(m, name, "case " + c.id); };
  ConvergeRow row;
  row.scene = c.scene;
  row.control_points = c.labels.value("control_points", std::size_t{0});
  row.residual_crush_m = number("residual_crush_m");
  row.max_residual_crush_m = number("max_residual_crush_m");
  row.max_dynamic_crush_m = number("max_dynamic_crush_m");
  row.max_dent_m = number("max_dent_m");
  row.crushed_volume_m3 = number("crushed_volume_m3");
  row.restitution = number("restitution");
  row.plastic_work_J = number("plastic_work_J");
  row.kinetic_initial_J = number("kinetic_initial_J");
  row.deform_ms = number("deform_ms");
  if (m.contains("surface_residual_crush_m")) row.surface_crush_m = number("surface_residual_crush_m");
  if (m.contains("contact_work_J")) row.contact_work_J = number("contact_work_J");
  // Written before the profile was measured: none (the tables leave it out).
  const auto profile = m.find("crush_profile_m");
  if (profile != m.end() && profile->is_array()) {
    for (const nlohmann::json& station : *profile)  // null: a NaN written out (the line missed the surface)
      row.crush_profile_m.push_back(station.is_number() ? station.get<double>() : std::nan(""));
    row.crush_height_m = number("crush_height_m");
  }
  return row;
}

/// The stations' crush, space separated or one table cell each ("-": the line missed the surface) [m].
std::string profileText(const std::vector<double>& profile_m, const char* between) {
  std::string text;
  for (std::size_t j = 0; j < profile_m.size(); ++j)
    text +=
        (j ? between : "") + (std::isnan(profile_m[j]) ? std::string("-") : CsvTable::fixed(profile_m[j], 3));
  return text;
}

/// Where along the width each level gains or loses crush: the stations per level. Empty when the rows
/// carry no profile.
std::string profileTable(const std::vector<ConvergeRow>& rows, const std::string& name) {
  std::size_t stations = 0;
  for (const ConvergeRow& r : rows)
    if (r.scene == name) stations = std::max(stations, r.crush_profile_m.size());
  if (stations == 0) return "";
  std::ostringstream md;
  md << "\nThe stations behind the residual crush (C1 to C" << stations
     << " across the struck side, at the height of its most protruding control point; - where the line "
        "misses the control surface), m:\n\n| control points | height m |";
  for (std::size_t j = 0; j < stations; ++j) md << " C" << j + 1 << " |";
  md << "\n|---|---|";
  for (std::size_t j = 0; j < stations; ++j) md << "---|";
  md << "\n";
  for (const ConvergeRow& r : rows)
    if (r.scene == name && !r.crush_profile_m.empty())
      md << "| " << r.control_points << " | " << CsvTable::fixed(r.crush_height_m, 3) << " | "
         << profileText(r.crush_profile_m, " | ") << " |\n";
  return md.str();
}

void writeOutputs(const std::vector<ConvergeRow>& rows, const std::vector<std::string>& names,
                  const std::string& dir) {
  CsvTable csv({"scene", "control_points", "residual_crush_m", "max_residual_crush_m", "max_dynamic_crush_m",
                "max_dent_m", "restitution", "plastic_work_J", "kinetic_initial_J", "change_from_finest",
                "deform_ms", "crushed_volume_m3", "volume_change_from_finest", "crush_height_m",
                "crush_profile_m", "surface_residual_crush_m", "surface_change_from_finest", "contact_work_J",
                "contact_work_change_from_finest"});
  std::ostringstream md;
  md << "Residual crush (six-station average) and crushed volume (the control surface's, at rest less now) "
        "against the level of detail, and the same six stations on the car's own surface (its render mesh "
        "as the skin moves it, at the height of its most protruding vertex: the same rest shape at every "
        "level); the energy the obstacle put into the body (its work on the body in the chassis's frame); "
        "each change is against the finest level.\n";
  for (const std::string& name : names) {
    md << "\n### " << name << "\n\n| control points | residual crush m | largest m | dynamic crush m "
       << "| deepest dent m | restitution | plastic / impact energy | change from finest | crushed volume L "
       << "| its change | car's surface: crush m | its change | into the body kJ | its change | deform ms |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const ConvergeRow& r : rows) {
      if (r.scene != name) continue;
      csv.addRow({r.scene, std::to_string(r.control_points), CsvTable::number(r.residual_crush_m),
                  CsvTable::number(r.max_residual_crush_m), CsvTable::number(r.max_dynamic_crush_m),
                  CsvTable::number(r.max_dent_m), CsvTable::number(r.restitution),
                  CsvTable::number(r.plastic_work_J), CsvTable::number(r.kinetic_initial_J),
                  CsvTable::number(r.change_from_finest), CsvTable::number(r.deform_ms),
                  CsvTable::number(r.crushed_volume_m3), CsvTable::number(r.volume_change_from_finest),
                  CsvTable::number(r.crush_height_m), profileText(r.crush_profile_m, " "),
                  CsvTable::number(r.surface_crush_m), CsvTable::number(r.surface_change_from_finest),
                  CsvTable::number(r.contact_work_J), CsvTable::number(r.contact_work_change_from_finest)});
      md << "| " << r.control_points << " | " << CsvTable::fixed(r.residual_crush_m, 3) << " | "
         << CsvTable::fixed(r.max_residual_crush_m, 3) << " | " << CsvTable::fixed(r.max_dynamic_crush_m, 3)
         << " | " << CsvTable::fixed(r.max_dent_m, 3) << " | " << CsvTable::fixed(r.restitution, 3) << " | "
         << CsvTable::fixed(100 * r.plastic_work_J / std::max(r.kinetic_initial_J, 1e-9), 0) << " % | "
         << (r.change_from_finest >= 0 ? "+" : "") << CsvTable::fixed(100 * r.change_from_finest, 1)
         << " % | " << CsvTable::fixed(1e3 * r.crushed_volume_m3, 1) << " | "
         << (r.volume_change_from_finest >= 0 ? "+" : "")
         << CsvTable::fixed(100 * r.volume_change_from_finest, 1) << " % | "
         << (std::isnan(r.surface_crush_m) ? std::string("-") : CsvTable::fixed(r.surface_crush_m, 3))
         << " | "
         << (std::isnan(r.surface_crush_m)
                 ? std::string("-")
                 : (r.surface_change_from_finest >= 0 ? "+" : "") +
                       CsvTable::fixed(100 * r.surface_change_from_finest, 1) + " %")
         << " | "
         << (std::isnan(r.contact_work_J) ? std::string("-") : CsvTable::fixed(1e-3 * r.contact_work_J, 1))
         << " | "
         << (std::isnan(r.contact_work_J)
                 ? std::string("-")
                 : (r.contact_work_change_from_finest >= 0 ? "+" : "") +
                       CsvTable::fixed(100 * r.contact_work_change_from_finest, 1) + " %")
         << " | " << CsvTable::fixed(r.deform_ms, 0) << " |\n";
    }
    md << profileTable(rows, name);
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
        points << r.control_points << "," << r.residual_crush_m << "," << r.max_dent_m << ","
               << 1e3 * r.crushed_volume_m3 << ","
               << (std::isnan(r.surface_crush_m) ? std::string("NaN") : std::to_string(r.surface_crush_m))
               << "\n";
    scenes::writeFileAtomically(data, points.str());
    const std::string colour = colours[k % 4];
    gp << (k ? ", \\\n  " : "") << gnuplotQuoted(data) << " using 1:2 with linespoints lw 2 pt 7 lc rgb '"
       << colour << "' title " << gnuplotQuoted(names[k] + ": residual crush (6 stations, control surface)")
       << ", \\\n  " << gnuplotQuoted(data) << " using 1:5 with linespoints lw 2 pt 5 lc rgb '" << colour
       << "' title " << gnuplotQuoted(names[k] + ": the same on the car's surface (render mesh)")
       << ", \\\n  " << gnuplotQuoted(data) << " using 1:3 with linespoints lw 1 dt 2 pt 6 lc rgb '" << colour
       << "' title " << gnuplotQuoted(names[k] + ": deepest dent");
  }
  gp << "\n";
  if (runGnuplot(base + ".gp", gp.str())) std::printf("wrote %s.png\n", base.c_str());

  // Crushed volume against N: what the material absorbs energy for, whatever the dent's shape.
  std::ostringstream volume;
  volume
      << "set terminal pngcairo size 1100,700 font 'DejaVu Sans,11' noenhanced\n"
      << "set output " << gnuplotQuoted(base + "_volume.png") << "\n"
      << "set title 'Crushed volume against the level of detail (built-in sedan)'\n"
      << "set logscale x\nset grid\nset key bottom right box opaque\nset xrange [40:3000]\nset yrange [0:*]\n"
      << "set xlabel 'control points N'\nset ylabel 'crushed volume [L]'\nset datafile separator ','\n"
      << "plot ";
  for (std::size_t k = 0; k < names.size(); ++k)
    volume << (k ? ", \\\n  " : "") << gnuplotQuoted(base + "_" + names[k] + ".csv")
           << " using 1:4 with linespoints lw 2 pt 7 lc rgb '" << colours[k % 4] << "' title "
           << gnuplotQuoted(names[k]);
  volume << "\n";
  if (runGnuplot(base + "_volume.gp", volume.str())) std::printf("wrote %s_volume.png\n", base.c_str());
}

}  // namespace

SweepPlan planConverge(const ConvergeOptions& options) {
  const std::vector<std::string> names = {"wall_crash", "pole_side"};
  const std::vector<std::size_t> levels = options.quick
                                              ? std::vector<std::size_t>{60, 250}
                                              : std::vector<std::size_t>{60, 120, 250, 500, 1000, 2000};
  SweepPlan plan;
  plan.kind = "converge";
  plan.version = buildVersion();
  plan.options = {{"quick", options.quick}, {"sets", options.sets}, {"scenes", names}};
  std::vector<scenes::Override> sets;
  for (const std::string& set : options.sets) sets.push_back(scenes::parseOverride(set));
  for (const std::string& name : names) {
    scenes::loadScene(name, sets);  // a bad key is refused now, naming it
    for (std::size_t n : levels) {
      std::vector<std::string> overrides = options.sets;
      overrides.push_back("vehicle.deformation.control_points=" + std::to_string(n));
      addCase(plan, name, overrides, "crash", {{"control_points", n}});
    }
  }
  return plan;
}

void writeConvergeReport(const SweepPlan& plan, const std::vector<nlohmann::json>& measured,
                         const std::string& dir) {
  std::vector<ConvergeRow> rows;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < plan.cases.size(); ++i) {
    rows.push_back(rowOf(plan.cases[i], measured[i]));
    if (std::find(names.begin(), names.end(), rows.back().scene) == names.end())
      names.push_back(rows.back().scene);
    std::printf("%s, %zu points: residual crush %.3f m (the car's surface %.3f m)\n",
                rows.back().scene.c_str(), rows.back().control_points, rows.back().residual_crush_m,
                rows.back().surface_crush_m);
  }
  std::fflush(stdout);
  for (const std::string& name : names) {
    // The last (finest) level of the scene.
    double finest = 0, finest_volume = 0, finest_surface = 0, finest_work = 0;
    for (const ConvergeRow& r : rows)
      if (r.scene == name) {
        finest = r.residual_crush_m;
        finest_volume = r.crushed_volume_m3;
        finest_surface = r.surface_crush_m;
        finest_work = r.contact_work_J;
      }
    for (ConvergeRow& r : rows) {
      if (r.scene != name) continue;
      r.change_from_finest = finest > 0 ? r.residual_crush_m / finest - 1.0 : 0.0;
      r.volume_change_from_finest = finest_volume > 0 ? r.crushed_volume_m3 / finest_volume - 1.0 : 0.0;
      r.surface_change_from_finest = finest_surface > 0 ? r.surface_crush_m / finest_surface - 1.0 : 0.0;
      r.contact_work_change_from_finest = finest_work > 0 ? r.contact_work_J / finest_work - 1.0 : 0.0;
    }
  }
  std::filesystem::create_directories(dir);
  writeOutputs(rows, names, dir);
}

}  // namespace sandbox
