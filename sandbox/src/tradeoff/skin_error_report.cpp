#include "tradeoff/skin_error_report.hpp"

#include "tradeoff/known_fields.hpp"

#include "plot.hpp"
#include "table_output.hpp"

#include <scenes/scene_run.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace sandbox {
namespace {

constexpr double kAlpha = 3.5;  // the balanced preset's power, for the tables against N and K
constexpr std::size_t kK = 8;
const char* const kFields[] = {"bend", "twist", "crush", "affine", "wall_crash"};
const char* const kMethods[] = {"idw", "mls"};

/// Millimetres with three significant figures (the affine rows of mls are near float rounding).
std::string mm(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", 1e3 * metres);
  return text;
}

/// The values of `member` over the rows, sorted; the spline's rows (k 0 and alpha 0: it has neither) are
/// left out of the K and alpha lists.
template <class T>
std::vector<T> distinct(const std::vector<SkinErrorRow>& rows, T SkinErrorRow::*member) {
  std::vector<T> values;
  for (const auto& r : rows) {
    if (r.method == "spline" && r.*member == T{}) continue;  // the spline has no K or alpha
    if (std::find(values.begin(), values.end(), r.*member) == values.end()) values.push_back(r.*member);
  }
  std::sort(values.begin(), values.end());
  return values;
}

void targetTable(std::ostringstream& md, const std::vector<SkinErrorRow>& rows, std::size_t n) {
  md << "\n### The target: mls halves the RMS error of idw at N = " << n << ", K = " << kK
     << ", alpha = " << kAlpha << " (and the spline through every point, beside them)\n\n"
     << "| field | largest motion mm | idw RMS mm | mls RMS mm | mls / idw | spline RMS mm | spline / idw "
        "| idw max mm | mls max mm | spline max mm | halved by mls? | by the spline? |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const char* field : kFields) {
    const SkinErrorRow* idw = findSkinErrorRow(rows, field, "idw", n, kK, kAlpha);
    const SkinErrorRow* mls = findSkinErrorRow(rows, field, "mls", n, kK, kAlpha);
    if (!idw || !mls) continue;
    const SkinErrorRow* spline = findSkinErrorRow(rows, field, "spline", n, 0, 0.0);
    const double ratio = mls->rms_error_m / idw->rms_error_m;
    const double spline_ratio = spline ? spline->rms_error_m / idw->rms_error_m : NAN;
    md << "| " << field << " | " << CsvTable::fixed(1e3 * idw->field_max_m, 0) << " | "
       << mm(idw->rms_error_m) << " | " << mm(mls->rms_error_m) << " | " << CsvTable::fixed(ratio, 3) << " | "
       << (spline ? mm(spline->rms_error_m) : "") << " | " << (spline ? CsvTable::fixed(spline_ratio, 3) : "")
       << " | " << mm(idw->max_error_m) << " | " << mm(mls->max_error_m) << " | "
       << (spline ? mm(spline->max_error_m) : "") << " | " << (ratio <= 0.5 ? "**yes**" : "no") << " | "
       << (spline ? (spline_ratio <= 0.5 ? "**yes**" : "no") : "") << " |\n";
  }
}

void trendTable(std::ostringstream& md, const std::vector<SkinErrorRow>& rows, bool largest) {
  md << "\n### " << (largest ? "Largest" : "RMS") << " vertex error [mm] against N (K = " << kK
     << ", alpha = " << kAlpha << ")\n\n| N (built) |";
  for (const char* field : kFields)
    md << " " << field << " idw | " << field << " mls | " << field << " spline |";
  md << "\n|---|";
  for (std::size_t i = 0; i < 3 * std::size(kFields); ++i) md << "---|";
  md << "\n";
  for (const std::size_t n : distinct(rows, &SkinErrorRow::target_points)) {
    const SkinErrorRow* any = findSkinErrorRow(rows, "bend", "idw", n, kK, kAlpha);
    if (!any) continue;
    md << "| " << n << " (" << any->control_points << ") |";
    for (const char* field : kFields) {
      for (const char* method : kMethods) {
        const SkinErrorRow* r = findSkinErrorRow(rows, field, method, n, kK, kAlpha);
        md << " " << (r ? mm(largest ? r->max_error_m : r->rms_error_m) : "") << " |";
      }
      // Past kSplineMostControlPoints there is no spline: the cell stays empty.
      const SkinErrorRow* spline = findSkinErrorRow(rows, field, "spline", n, 0, 0.0);
      md << " " << (spline ? mm(largest ? spline->max_error_m : spline->rms_error_m) : "") << " |";
    }
    md << "\n";
  }
}

/// RMS [mm] at the smallest N, one row per K and alpha.
void knobTable(std::ostringstream& md, const std::vector<SkinErrorRow>& rows, std::size_t n) {
  md << "\n### RMS vertex error [mm] against K and alpha at N = " << n << "\n\n| K | alpha |";
  for (const char* field : kFields) md << " " << field << " idw | " << field << " mls |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < 2 * std::size(kFields); ++i) md << "---|";
  md << "\n";
  for (const std::size_t k : distinct(rows, &SkinErrorRow::k)) {
    for (const double alpha : distinct(rows, &SkinErrorRow::alpha)) {
      md << "| " << k << " | " << alpha << " |";
      for (const char* field : kFields) {
        for (const char* method : kMethods) {
          const SkinErrorRow* r = findSkinErrorRow(rows, field, method, n, k, alpha);
          md << " " << (r ? mm(r->rms_error_m) : "") << " |";
        }
      }
      md << "\n";
    }
  }
}

/// One panel per field: error [mm] against N, log-log, one line per method (colour) and K (dash).
void plotErrors(const std::vector<SkinErrorRow>& rows, const std::string& dir, bool largest) {
  const std::string name = largest ? "skin_error_max" : "skin_error_rms";
  const std::string base = dir + "/" + name;
  const std::vector<std::size_t> ks = distinct(rows, &SkinErrorRow::k);
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1200,1300 font 'DejaVu Sans,11' noenhanced\n"
     << "set output " << gnuplotQuoted(base + ".png") << "\n"
     << "set multiplot layout 3,2 title "
     << gnuplotQuoted(std::string("The skin alone: ") + (largest ? "largest" : "RMS") +
                      " render-vertex error against N on known fields (builtin:sedan, 20,000 vertices, "
                      "alpha = 3.5)")
     << "\nset logscale xy\nset grid\nset format y '%g'\nset key outside right top font ',9'\nset xrange "
        "[40:3000]\n"
     << "set xlabel 'control points N'\nset ylabel '" << (largest ? "largest" : "RMS")
     << " vertex error [mm]'\n";
  for (const char* field : kFields) {
    const std::string data = base + "_" + field + ".dat";
    std::ostringstream dat;
    dat << "# N";
    for (const char* method : kMethods)
      for (const std::size_t k : ks) dat << " " << method << "_K" << k;
    dat << " spline\n";
    for (const std::size_t n : distinct(rows, &SkinErrorRow::target_points)) {
      const SkinErrorRow* any = findSkinErrorRow(rows, field, "idw", n, ks.front(), kAlpha);
      if (!any) continue;
      dat << any->control_points;
      for (const char* method : kMethods) {
        for (const std::size_t k : ks) {
          const SkinErrorRow* r = findSkinErrorRow(rows, field, method, n, k, kAlpha);
          const double e_m = r ? (largest ? r->max_error_m : r->rms_error_m) : NAN;
          dat << " " << std::max(1e3 * e_m, 1e-5);  // log axis: float rounding floor
        }
      }
      const SkinErrorRow* spline = findSkinErrorRow(rows, field, "spline", n, 0, 0.0);
      if (spline)
        dat << " " << std::max(1e3 * (largest ? spline->max_error_m : spline->rms_error_m), 1e-5);
      else
        dat << " NaN";  // past kSplineMostControlPoints: no point
      dat << "\n";
    }
    scenes::writeFileAtomically(data, dat.str());
    gp << "set title '" << field << "'\nplot ";
    int column = 2;
    const char* dashes[] = {"2", "1", "3"};
    for (std::size_t m = 0; m < std::size(kMethods); ++m) {
      for (std::size_t i = 0; i < ks.size(); ++i, ++column) {
        gp << (column > 2 ? ", \\\n  " : "") << gnuplotQuoted(data) << " using 1:" << column
           << " with linespoints lw " << (ks[i] == kK ? 2.5 : 1.5) << " dt " << dashes[i % 3] << " pt "
           << (m == 0 ? 7 : 5) << " ps 0.9 lc rgb '" << (m == 0 ? "#d62728" : "#1f77b4") << "' title '"
           << kMethods[m] << " K=" << ks[i] << "'";
      }
    }
    gp << ", \\\n  " << gnuplotQuoted(data) << " using 1:" << column
       << " with linespoints lw 2.5 dt 1 pt 9 ps 1.1 lc rgb '#2ca02c' title 'spline (N <= 256)'\n";
  }
  gp << "unset multiplot\n";
  if (runGnuplot(base + ".gp", gp.str())) std::printf("wrote %s.png\n", base.c_str());
}

}  // namespace

const SkinErrorRow* findSkinErrorRow(const std::vector<SkinErrorRow>& rows, const std::string& field,
                                     const std::string& method, std::size_t target_points, std::size_t k,
                                     double alpha) {
  for (const auto& r : rows)
    if (r.field == field && r.method == method && r.target_points == target_points && r.k == k &&
        r.alpha == alpha)
      return &r;
  return nullptr;
}

std::string skinErrorCsv(const std::vector<SkinErrorRow>& rows) {
  CsvTable csv({"field", "method", "control_points", "target_points", "k", "alpha", "rms_error_mm",
                "max_error_mm", "field_max_mm"});
  for (const auto& r : rows)
    csv.addRow({r.field, r.method, std::to_string(r.control_points), std::to_string(r.target_points),
                std::to_string(r.k), CsvTable::number(r.alpha), CsvTable::number(1e3 * r.rms_error_m),
                CsvTable::number(1e3 * r.max_error_m), CsvTable::number(1e3 * r.field_max_m)});
  return csv.text();
}

std::string skinErrorMarkdown(const std::vector<SkinErrorRow>& rows, const std::string& command) {
  std::ostringstream md;
  md << "`" << command << "`: the built-in sedan's control mesh moved by known smooth fields, the "
     << "render mesh (builtin:sedan, 20,000 vertices) deformed by the skin and compared with the field "
     << "applied to each vertex (tradeoff/known_fields.hpp). Vehicle frame: +x forward, s = x - x_c, h = z - "
        "z_c, "
     << "y' = y - y_c about the bounding box's centre, L = length, W = width.\n\n";
  for (const KnownField& f : knownFields(deform::Aabb{}))
    md << "- **" << f.name << "**: " << f.formula << "\n";
  if (std::any_of(rows.begin(), rows.end(), [](const SkinErrorRow& r) { return r.field == "wall_crash"; }))
    md << "- **wall_crash**: the residual dent of `wall_crash` (56 km/h) at the finest model's control "
          "points, "
          "smoothed by a Gaussian kernel average (tradeoff/crash_field.hpp)\n";
  const std::vector<std::size_t> ns = distinct(rows, &SkinErrorRow::target_points);
  if (ns.empty()) return md.str();
  targetTable(md, rows, ns.front());
  trendTable(md, rows, false);
  trendTable(md, rows, true);
  knobTable(md, rows, ns.front());
  return md.str();
}

void writeSkinErrorReport(const std::vector<SkinErrorRow>& rows, const std::string& dir,
                          const std::string& command) {
  scenes::writeFileAtomically(dir + "/skin_error.csv", skinErrorCsv(rows));
  scenes::writeFileAtomically(dir + "/skin_error.md", skinErrorMarkdown(rows, command));
  std::printf("wrote %s/skin_error.csv, %s/skin_error.md\n", dir.c_str(), dir.c_str());
  plotErrors(rows, dir, false);
  plotErrors(rows, dir, true);
}

}  // namespace sandbox
