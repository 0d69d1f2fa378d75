// `sandbox bench grid`: vertices against control points (grid/bench_grid.hpp) as CSV, Markdown and a
// log-log plot of the per-frame cost, one line per control-point count, the baselines beside them.
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "grid/bench_grid.hpp"
#include "plot.hpp"
#include "table_output.hpp"

#include <scenes/scene_run.hpp>

namespace sandbox {
namespace {

struct GridFlags {
  std::string out_dir = "out/grid";
  bool quick = false;
  unsigned threads = 0;
};

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

void runGrid(const GridFlags& flags) {
  GridOptions options = flags.quick ? GridOptions::quick() : GridOptions{};
  options.threads = flags.threads;
  std::filesystem::create_directories(flags.out_dir);
  const std::vector<GridRow> rows = runBenchGrid(options, printRow);
  scenes::writeFileAtomically(flags.out_dir + "/grid.csv", csvText(rows));
  std::printf("wrote %s/grid.csv\n", flags.out_dir.c_str());
  CsvTable crashes({"speed_kmh", "stable", "finite", "tunnelled", "max_extent_growth", "max_node_speed_mps",
                    "residual_dent_m", "verdict"});
  for (const baselines::SoftBodyCrash& c : bulletCrashes(options)) {
    std::printf("Bullet soft body (60-point control mesh) in wall_crash at %g km/h: %s\n", c.speed_kmh,
                c.verdict.c_str());
    crashes.addRow({CsvTable::number(c.speed_kmh), c.stable ? "1" : "0", c.finite ? "1" : "0",
                    c.tunnelled ? "1" : "0", CsvTable::number(c.max_extent_growth),
                    CsvTable::number(c.max_node_speed_mps), CsvTable::number(c.residual_dent_m), c.verdict});
  }
  scenes::writeFileAtomically(flags.out_dir + "/bullet_crash.csv", crashes.text());
  plot(rows, flags.out_dir);
}

}  // namespace

void registerBenchGridCommand(CLI::App& bench) {
  auto flags = std::make_shared<GridFlags>();
  auto* cmd = bench.add_subcommand("grid", "Render-mesh vertices against control points, with the baselines");
  cmd->add_option("--out", flags->out_dir, "Folder for grid.csv and grid.png")->capture_default_str();
  cmd->add_flag("--quick", flags->quick, "10k and 100k vertices, 8, 60 and 1000 points (under 2 min)");
  cmd->add_option("--threads", flags->threads, "Threads of the embedding pass (0 = all cores)")
      ->capture_default_str();
  cmd->callback([flags] { runGrid(*flags); });
}

}  // namespace sandbox
