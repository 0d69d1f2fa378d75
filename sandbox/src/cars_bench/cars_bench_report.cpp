// `sandbox bench cars`: CSV, Markdown and the plot (cars_bench.hpp).
#include "cars_bench.hpp"

#include <scenes/scene_run.hpp>

#include <filesystem>
#include <map>
#include <sstream>

#include "../plot.hpp"
#include "../table_output.hpp"

namespace sandbox {
namespace {

// The stages of a row, in the order they run, with their names.
std::vector<std::pair<const char*, double>> stages(const CarsBenchRow& r) {
  return {{"tyres", r.tyres_ms},   {"collide", r.collide_ms},   {"solve", r.solve_ms},
          {"deform", r.deform_ms}, {"coupling", r.coupling_ms}, {"metrics", r.metrics_ms}};
}

// Whether every thread count of `cars` gave the same state hash.
bool sameHash(const std::vector<CarsBenchRow>& rows, std::size_t cars) {
  std::string first;
  for (const CarsBenchRow& r : rows) {
    if (r.cars != cars) continue;
    if (first.empty()) first = r.state_hash;
    if (r.state_hash != first) return false;
  }
  return true;
}

void writePlot(const std::string& dir, const std::vector<CarsBenchRow>& rows, const std::vector<int>& threads,
               bool skip_when_idle) {
  // One block per line: each stage on the first thread count, then the whole step on every count.
  std::ostringstream data;
  std::vector<std::string> titles;
  const int first = threads.front();
  for (const auto& [stage, unused] : stages(CarsBenchRow{})) {
    (void)unused;
    data << "# " << stage << ", " << first << " thread(s)\n";
    for (const CarsBenchRow& r : rows)
      if (r.threads == first)
        for (const auto& [name, ms] : stages(r))
          if (std::string(name) == stage) data << r.cars << " " << std::max(ms, 1e-3) << "\n";
    data << "\n\n";
    titles.push_back(std::string(stage) + " (" + std::to_string(first) + " thread" + (first == 1 ? "" : "s") +
                     ")");
  }
  for (int t : threads) {
    data << "# whole step, " << t << " thread(s)\n";
    for (const CarsBenchRow& r : rows)
      if (r.threads == t) data << r.cars << " " << std::max(r.step_ms, 1e-3) << "\n";
    data << "\n\n";
    titles.push_back("whole step (" + std::to_string(t) + " thread" + (t == 1 ? "" : "s") + ")");
  }
  scenes::writeFileAtomically(dir + "/cars.dat", data.str());
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1200,760 font 'DejaVu Sans,11' noenhanced\n"
     << "set output " << gnuplotQuoted(dir + "/cars.png") << "\n"
     << "set title 'Cost per simulated second against cars: sedans cruising at 50 km/h, 60 Hz, no obstacle"
     << (skip_when_idle ? ", idle cars asleep" : ", skip_when_idle off") << "'\n"
     << "set logscale xy\nset grid\nset key bottom right font ',9'\n"
     << "set xlabel 'cars'\nset ylabel 'wall ms per simulated second'\n"
     << "set arrow from graph 0, first 1000 to graph 1, first 1000 nohead dt 3\n"
     << "set label 'real time' at graph 0.02, first 1150\n"
     << "plot ";
  for (std::size_t i = 0; i < titles.size(); ++i) {
    const bool whole = i >= titles.size() - threads.size();
    gp << (i ? ", \\\n  " : "") << gnuplotQuoted(dir + "/cars.dat") << " index " << i
       << " using 1:2 with linespoints lw " << (whole ? 3 : 2) << " pt " << (whole ? 5 : 7)
       << (whole ? "" : " dt 2") << " title " << gnuplotQuoted(titles[i]);
  }
  gp << "\n";
  if (runGnuplot(dir + "/cars.gp", gp.str())) std::printf("wrote %s/cars.png\n", dir.c_str());
}

}  // namespace

void writeCarsBenchReport(const CarsBenchOptions& options, const std::vector<CarsBenchRow>& rows) {
  const std::string& dir = options.out_dir;
  std::filesystem::create_directories(dir);
  CsvTable csv({"cars", "threads", "setup_ms", "tyres_ms_per_s", "collide_ms_per_s", "solve_ms_per_s",
                "deform_ms_per_s", "coupling_ms_per_s", "metrics_ms_per_s", "step_ms_per_s", "x_real_time",
                "state_hash", "budget_ms", "budget_estimated_ms", "deform_ms_per_step", "levels"});
  for (const CarsBenchRow& r : rows) {
    std::vector<std::string> cells = {std::to_string(r.cars), std::to_string(r.threads),
                                      CsvTable::number(r.setup_ms)};
    for (const auto& [name, ms] : stages(r)) cells.push_back(CsvTable::number(ms));
    cells.push_back(CsvTable::number(r.step_ms));
    cells.push_back(CsvTable::number(r.realtime_factor()));
    cells.push_back(r.state_hash);
    cells.push_back(options.budget_ms ? CsvTable::number(*options.budget_ms) : "");
    cells.push_back(options.budget_ms ? CsvTable::number(r.budget_estimated_ms) : "");
    cells.push_back(options.budget_ms ? CsvTable::number(r.budget_measured_ms) : "");
    cells.push_back(r.levels);
    csv.addRow(cells);
  }
  scenes::writeFileAtomically(dir + "/cars.csv", csv.text());

  std::ostringstream md;
  md << "Built-in sedans (20k vertices, 60 control points) cruising at 50 km/h under speed control, "
     << CsvTable::fixed(options.physics_hz, 0) << " Hz, " << CsvTable::fixed(options.duration_s, 1)
     << " s simulated, no obstacle"
     << (options.skip_when_idle ? ", idle cars asleep (`skip_when_idle`, the default)"
                                : ", `skip_when_idle` false (a body wakes on the chassis's loads)")
     << ". Stages in wall ms per simulated second.\n\n"
     << "| cars | threads | set-up ms | tyres | collide | solve | deform | coupling | metrics | step | x "
        "real "
        "time | hash same on all thread counts |\n"
     << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const CarsBenchRow& r : rows) {
    md << "| " << r.cars << " | " << r.threads << " | " << CsvTable::fixed(r.setup_ms, 0);
    for (const auto& [name, ms] : stages(r)) md << " | " << CsvTable::fixed(ms, 1);
    md << " | " << CsvTable::fixed(r.step_ms, 0) << " | " << CsvTable::fixed(r.realtime_factor(), 1) << " | "
       << (sameHash(rows, r.cars) ? "yes" : "**no**") << " |\n";
  }
  if (options.budget_ms) {
    md << "\nDeformation budget " << CsvTable::fixed(*options.budget_ms, 3)
       << " ms per physics step (`--budget-ms`): the plan's estimate (every body awake) and deform's "
          "measured "
          "time per physics step, every car together.\n\n"
       << "| cars | threads | levels | estimated ms | measured ms | measured / budget | within 20 % |\n"
       << "|---:|---:|---|---:|---:|---:|---|\n";
    // The budget holds when deform's measured time is within 20 % of it (issue 12), where the plan could
    // meet it (a budget below the coarsest levels says so and is not a miss).
    std::size_t held = 0, meetable = 0;
    for (const CarsBenchRow& r : rows) {
      const bool can = r.budget_estimated_ms <= *options.budget_ms;
      const bool within = r.budget_measured_ms <= 1.2 * *options.budget_ms;
      meetable += can ? 1 : 0;
      held += can && within ? 1 : 0;
      md << "| " << r.cars << " | " << r.threads << " | " << r.levels << " | "
         << CsvTable::fixed(r.budget_estimated_ms, 3) << " | " << CsvTable::fixed(r.budget_measured_ms, 3)
         << " | " << CsvTable::fixed(r.budget_measured_ms / *options.budget_ms, 2) << " | "
         << (!can     ? "not meetable"
             : within ? "yes"
                      : "**no**")
         << " |\n";
    }
    md << "\nThe budget held within 20 % in " << held << " of the " << meetable
       << " runs it could be met in.\n";
    std::printf("deformation budget held within 20 %% in %zu of the %zu runs it could be met in\n", held,
                meetable);
  }
  scenes::writeFileAtomically(dir + "/cars.md", md.str());
  std::printf("wrote %s/cars.csv, %s/cars.md\n", dir.c_str(), dir.c_str());
  if (!options.threads.empty()) writePlot(dir, rows, options.threads, options.skip_when_idle);
}

}  // namespace sandbox
