// The trade-off report (tradeoff.hpp, writeTradeoffReport): tradeoff.csv, tradeoff.md and one Pareto plot
// per scene, from the rows of `sandbox tradeoff` or of `sandbox sweep merge` on a tradeoff plan.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "plot.hpp"
#include "table_output.hpp"
#include "tradeoff/tradeoff.hpp"

#include <scenes/scene_run.hpp>

namespace sandbox {
namespace {

std::string csvText(const std::vector<TradeoffRow>& rows) {
  CsvTable csv({"scene", "knob", "value", "overrides", "physics_ms", "deform_ms", "embed_ms", "total_ms",
                "rms_error_mm", "max_error_mm", "rms_error_fraction", "max_error_fraction",
                "residual_crush_m", "crush_error_mm", "strain_residual", "pareto"});
  for (const TradeoffRow& r : rows) {
    std::string overrides;
    for (const std::string& o : r.overrides) overrides += (overrides.empty() ? "" : " ") + o;
    csv.addRow({r.scene, r.knob, r.value, overrides, CsvTable::number(r.physics_ms),
                CsvTable::number(r.deform_ms), CsvTable::number(r.embed_ms), CsvTable::number(r.total_ms()),
                CsvTable::number(r.rms_error_mm), CsvTable::number(r.max_error_mm),
                CsvTable::number(r.rms_error_fraction), CsvTable::number(r.max_error_fraction),
                CsvTable::number(r.residual_crush_m), CsvTable::number(r.crush_error_mm),
                CsvTable::number(r.strain_residual), r.pareto ? "1" : "0"});
  }
  return csv.text();
}

std::string markdownText(const std::vector<TradeoffRow>& rows) {
  std::ostringstream md;
  std::string scene;
  for (const TradeoffRow& r : rows) {
    if (r.scene != scene) {
      scene = r.scene;
      md << "\n### " << scene
         << "\n\n| knob | value | ms/frame (physics + deform + embed) | RMS error mm | max mm "
         << "| RMS / diagonal | crush m | crush error mm | strain residual | front |\n"
         << "|---|---|---|---|---|---|---|---|---|---|\n";
    }
    md << "| " << r.knob << " | " << r.value << " | " << CsvTable::fixed(r.total_ms(), 3) << " ("
       << CsvTable::fixed(r.physics_ms, 3) << " + " << CsvTable::fixed(r.deform_ms, 3) << " + "
       << CsvTable::fixed(r.embed_ms, 3) << ") | " << CsvTable::fixed(r.rms_error_mm, 2) << " | "
       << CsvTable::fixed(r.max_error_mm, 1) << " | " << CsvTable::fixed(100 * r.rms_error_fraction, 3)
       << " % | " << CsvTable::fixed(r.residual_crush_m, 3) << " | " << CsvTable::fixed(r.crush_error_mm, 1)
       << " | " << CsvTable::fixed(r.strain_residual, 5) << " | " << (r.pareto ? "**yes**" : "") << " |\n";
  }
  return md.str();
}

// One Pareto plot per scene: every configuration, the front as a line, and labels on the presets and the
// front only, none closer than about a label's size to one already placed (the rest crowd together near
// the balanced preset; the table names them).
void plotScene(const std::vector<TradeoffRow>& rows, const std::string& scene, const std::string& dir) {
  std::ostringstream all, front;
  std::vector<const TradeoffRow*> shown, on_front;
  for (const TradeoffRow& r : rows)
    if (r.scene == scene && r.knob != "reference") shown.push_back(&r);
  // Presets first, then the front from the cheapest; a label is dropped where its text would overlap
  // one already kept. A label runs right of its point: about 0.016 decades of cost per character on the
  // plot's 1200 pixels, 0.05 decades of error high (plus a point's width either side).
  std::vector<const TradeoffRow*> order = shown;
  std::stable_sort(order.begin(), order.end(), [](const TradeoffRow* a, const TradeoffRow* b) {
    if ((a->knob == "preset") != (b->knob == "preset")) return a->knob == "preset";
    return a->total_ms() < b->total_ms();
  });
  std::vector<const TradeoffRow*> labelled;
  auto logOf = [](double v) { return std::log10(std::max(v, 1e-3)); };
  auto textOf = [](const TradeoffRow* r) { return (r->knob == "preset" ? "" : r->knob + "=") + r->value; };
  auto widthOf = [&](const TradeoffRow* r) { return 0.016 * static_cast<double>(textOf(r).size()) + 0.03; };
  for (const TradeoffRow* r : order) {
    if (r->knob != "preset" && !r->pareto) continue;
    bool crowded = false;
    const double x = logOf(r->total_ms()), y = logOf(r->rms_error_mm);
    for (const TradeoffRow* k : labelled) {
      const double kx = logOf(k->total_ms()), ky = logOf(k->rms_error_mm);
      const bool across = x < kx + widthOf(k) && kx < x + widthOf(r);
      crowded = crowded || (across && std::abs(y - ky) < 0.05);
    }
    if (!crowded) labelled.push_back(r);
  }
  for (const TradeoffRow* r : shown) {
    const double error_mm = std::max(r->rms_error_mm, 1e-3);  // log axis
    const bool label = std::find(labelled.begin(), labelled.end(), r) != labelled.end();
    all << r->total_ms() << " " << error_mm << " \"" << textOf(r) << "\" " << (r->knob == "preset" ? 1 : 0)
        << " " << (label ? 1 : 0) << "\n";
    if (r->pareto) on_front.push_back(r);
  }
  std::sort(on_front.begin(), on_front.end(),
            [](const TradeoffRow* a, const TradeoffRow* b) { return a->total_ms() < b->total_ms(); });
  for (const TradeoffRow* r : on_front)
    front << r->total_ms() << " " << std::max(r->rms_error_mm, 1e-3) << "\n";
  const std::string base = dir + "/tradeoff_" + scene;
  scenes::writeFileAtomically(base + ".dat", all.str());
  scenes::writeFileAtomically(base + "_front.dat", front.str());
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1200,760 font 'DejaVu Sans,11' noenhanced\n"
     << "set output " << gnuplotQuoted(base + ".png") << "\n"
     << "set title "
     << gnuplotQuoted(scene + ": cost against error, one knob at a time from the balanced preset")
     << "\nset logscale xy\nset grid\nset key top right\nset offsets graph 0, graph 0.25, 0, 0\n"
     << "set xlabel 'cost per 60 Hz frame: physics + deformation + embedding [ms]'\n"
     << "set ylabel 'RMS render-mesh distance from the reference after the crash [mm]'\n"
     << "plot " << gnuplotQuoted(base + ".dat")
     << " using 1:($4==0?$2:1/0) with points pt 7 ps 1.3 lc rgb '#7f7f7f' title 'one knob moved', \\\n"
     << "  '' using 1:($4==1?$2:1/0) with points pt 5 ps 1.8 lc rgb '#1f77b4' title 'presets', \\\n"
     << "  '' using 1:($5==1?$2:1/0):3 with labels offset char 0.8,0.5 left font ',9' notitle, \\\n"
     << "  " << gnuplotQuoted(base + "_front.dat")
     << " using 1:2 with lines lw 2.5 lc rgb '#d62728' title 'Pareto front'\n";
  if (runGnuplot(base + ".gp", gp.str())) std::printf("wrote %s.png\n", base.c_str());
}

}  // namespace

void writeTradeoffReport(const std::vector<TradeoffRow>& rows, const std::string& dir) {
  std::filesystem::create_directories(dir);
  scenes::writeFileAtomically(dir + "/tradeoff.csv", csvText(rows));
  scenes::writeFileAtomically(dir + "/tradeoff.md", markdownText(rows));
  std::printf("wrote %s/tradeoff.csv, %s/tradeoff.md\n", dir.c_str(), dir.c_str());
  std::vector<std::string> names;  // scene names as the runs report them (a path's stem)
  for (const TradeoffRow& r : rows) {
    if (std::find(names.begin(), names.end(), r.scene) == names.end()) names.push_back(r.scene);
  }
  for (const std::string& name : names) plotScene(rows, name, dir);
}

}  // namespace sandbox
