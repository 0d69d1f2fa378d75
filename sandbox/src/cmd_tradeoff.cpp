// `sandbox tradeoff`: the speed/accuracy sweep (tradeoff/tradeoff.hpp) as CSV, Markdown and Pareto plots.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "plot.hpp"
#include "table_output.hpp"
#include "tradeoff/skin_error_report.hpp"
#include "tradeoff/tradeoff.hpp"

#include <scenes/scene_run.hpp>

namespace sandbox {
namespace {

struct TradeoffFlags {
  TradeoffOptions options;
  std::vector<std::string> scenes;
  std::string out_dir = "out/tradeoff";
  bool skin_only = false;  ///< the skin alone on known fields (tradeoff/skin_error.hpp), no physics
};

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

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
    md << "| " << r.knob << " | " << r.value << " | " << fixed(r.total_ms(), 3) << " ("
       << fixed(r.physics_ms, 3) << " + " << fixed(r.deform_ms, 3) << " + " << fixed(r.embed_ms, 3) << ") | "
       << fixed(r.rms_error_mm, 2) << " | " << fixed(r.max_error_mm, 1) << " | "
       << fixed(100 * r.rms_error_fraction, 3) << " % | " << fixed(r.residual_crush_m, 3) << " | "
       << fixed(r.crush_error_mm, 1) << " | " << fixed(r.strain_residual, 5) << " | "
       << (r.pareto ? "**yes**" : "") << " |\n";
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
  // Presets first, then the front from the cheapest; a label is dropped within 0.12 decades of cost
  // and 0.06 decades of error of one already kept.
  std::vector<const TradeoffRow*> order = shown;
  std::stable_sort(order.begin(), order.end(), [](const TradeoffRow* a, const TradeoffRow* b) {
    if ((a->knob == "preset") != (b->knob == "preset")) return a->knob == "preset";
    return a->total_ms() < b->total_ms();
  });
  std::vector<const TradeoffRow*> labelled;
  auto logOf = [](double v) { return std::log10(std::max(v, 1e-3)); };
  for (const TradeoffRow* r : order) {
    if (r->knob != "preset" && !r->pareto) continue;
    bool crowded = false;
    for (const TradeoffRow* k : labelled)
      crowded = crowded || (std::abs(logOf(r->total_ms()) - logOf(k->total_ms())) < 0.12 &&
                            std::abs(logOf(r->rms_error_mm) - logOf(k->rms_error_mm)) < 0.06);
    if (!crowded) labelled.push_back(r);
  }
  for (const TradeoffRow* r : shown) {
    const double error_mm = std::max(r->rms_error_mm, 1e-3);  // log axis
    const bool label = std::find(labelled.begin(), labelled.end(), r) != labelled.end();
    all << r->total_ms() << " " << error_mm << " \"" << (r->knob == "preset" ? "" : r->knob + "=") << r->value
        << "\" " << (r->knob == "preset" ? 1 : 0) << " " << (label ? 1 : 0) << "\n";
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

void runTradeoffCommand(TradeoffFlags& flags) {
  if (flags.skin_only) {
    std::filesystem::create_directories(flags.out_dir);
    const bool quick = flags.options.quick;
    const auto rows = runSkinError(quick ? SkinErrorOptions::quick() : SkinErrorOptions{});
    writeSkinErrorReport(rows, flags.out_dir,
                         std::string("sandbox tradeoff --skin-only") + (quick ? " --quick" : ""));
    return;
  }
  if (!flags.scenes.empty()) flags.options.scenes = flags.scenes;
  std::filesystem::create_directories(flags.out_dir);
  const std::vector<TradeoffRow> rows = runTradeoff(flags.options);
  scenes::writeFileAtomically(flags.out_dir + "/tradeoff.csv", csvText(rows));
  scenes::writeFileAtomically(flags.out_dir + "/tradeoff.md", markdownText(rows));
  std::printf("wrote %s/tradeoff.csv, %s/tradeoff.md\n", flags.out_dir.c_str(), flags.out_dir.c_str());
  std::vector<std::string> names;  // scene names as the runs report them (a path's stem)
  for (const TradeoffRow& r : rows) {
    if (std::find(names.begin(), names.end(), r.scene) == names.end()) names.push_back(r.scene);
  }
  for (const std::string& name : names) plotScene(rows, name, flags.out_dir);
}

}  // namespace

void registerTradeoffCommand(CLI::App& app) {
  auto flags = std::make_shared<TradeoffFlags>();
  auto* cmd =
      app.add_subcommand("tradeoff", "Speed against accuracy: every knob's cost and error, Pareto plots");
  cmd->add_option("--scene", flags->scenes, "Scene to sweep (repeatable; default wall_crash and post_bumps)");
  cmd->add_option("--out", flags->out_dir, "Folder for tradeoff.csv, tradeoff.md and the plots")
      ->capture_default_str();
  cmd->add_flag("--quick", flags->options.quick, "Two values per knob and a lighter reference (under 2 min)");
  cmd->add_flag("--skin-only", flags->skin_only,
                "The skin alone: control points moved by known smooth fields (bend, twist, frontal crush, "
                "affine), the render mesh against the exact field for N, K, alpha and idw/mls; writes "
                "skin_error.csv, skin_error.md and plots");
  cmd->callback([flags] { runTradeoffCommand(*flags); });
}

}  // namespace sandbox
