#include "mesh_report.hpp"

#include "elapsed.hpp"

#include <deform/control_mesh.hpp>
#include <deform/masses.hpp>
#include <deform/skin_checks.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace sandbox {
namespace {

nlohmann::ordered_json vec(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

nlohmann::ordered_json meshReport(const deform::VehicleModel& model, const MeshReportOptions& options) {
  const deform::Mesh& body = model.body;
  const deform::Aabb box = deform::boundingBox(body);

  auto start = std::chrono::steady_clock::now();
  std::vector<Eigen::Vector3d> points;
  points.reserve(body.positions_m.size());
  for (const auto& p : body.positions_m) points.push_back(p.cast<double>());
  const deform::ControlMesh control =
      deform::buildControlMesh(points, options.control_points, model.source.c_str(), options.lod);
  const double control_ms = msSince(start);
  const deform::ControlMeshStats stats = deform::controlMeshStats(control);
  const deform::MassSplit masses = deform::distributeMass(control, options.vehicle_mass_kg);

  start = std::chrono::steady_clock::now();
  const deform::Skin skin = deform::Skin::build(body.positions_m, control.points_m, options.skin);
  const double skin_ms = msSince(start);

  // Embedding checks: partition of unity, and exact reproduction of a rigid translation.
  double sum_error = 0;
  for (std::size_t j = 0; j < skin.vertexCount(); ++j) {
    double sum = 0;
    for (std::size_t k = 0; k < skin.influences(); ++k) sum += skin.slotWeight(j, k);
    sum_error = std::max(sum_error, std::abs(sum - 1.0));
  }
  const Eigen::Vector3d shift_m(0.1, -0.2, 0.3);
  std::vector<Eigen::Vector3d> displacement(control.points_m.size(), shift_m);
  std::vector<Eigen::Vector3f> moved(body.positions_m.size());
  skin.deform(body.positions_m.data(), displacement.data(), moved.data(), options.skin.threads);
  double translation_error = 0;
  for (std::size_t j = 0; j < moved.size(); ++j)
    translation_error = std::max(
        translation_error, (moved[j].cast<double>() - body.positions_m[j].cast<double>() - shift_m).norm());

  // Linear precision: the control points moved by a crash-sized affine map, against the map itself.
  const deform::AffineMap affine = deform::crashSizedAffineMap(0.5 * (box.min_m + box.max_m));
  const double affine_error = deform::affineReproductionErrorMax(skin, body.positions_m, control.points_m,
                                                                 affine, options.skin.threads);
  const deform::SkinWeightSpread spread = deform::skinWeightSpread(skin);

  const auto [lightest, heaviest] =
      std::minmax_element(masses.point_mass_kg.begin(), masses.point_mass_kg.end());
  nlohmann::ordered_json report;
  report["source"] = model.source;
  report["vertices"] = body.positions_m.size();
  report["triangles"] = body.triangles.size();
  report["bbox_min"] = vec(box.min_m);
  report["bbox_max"] = vec(box.max_m);
  report["bbox_size_m"] = vec(box.size_m());
  report["wheels"] = model.wheels.size();
  report["hull_vertices"] = control.hull_vertex_count;
  report["control_points"] = control.points_m.size();
  report["control_triangles"] = control.triangles.size();
  report["control_edges"] = control.edges.size();
  report["lod_method"] = options.lod == deform::LodMethod::Even ? "even" : "simplify";
  report["largest_gap_m"] = stats.largest_gap_m;
  report["longest_edge_m"] = stats.longest_edge_m;
  report["shortest_edge_m"] = stats.shortest_edge_m;
  report["even_gap_m"] = std::sqrt(stats.surface_area_m2 / static_cast<double>(control.points_m.size()));
  report["mirror_symmetric"] = !control.mirror_of.empty();
  // The hull's own vertices, against the surface the control points span.
  const deform::ControlMesh hull = deform::convexHull(points, model.source.c_str());
  report["hull_shortfall_m"] = deform::controlSurfaceShortfall_m(
      control, std::vector<Eigen::Vector3d>(
                   hull.points_m.begin(),
                   hull.points_m.begin() + static_cast<std::ptrdiff_t>(hull.hull_vertex_count)));
  report["control_volume_m3"] = deform::enclosedVolume_m3(control.points_m, control.triangles);
  report["hull_volume_m3"] = hull.volume_m3;
  report["centre_of_mass_m"] = vec(control.centre_of_mass_m);
  report["mass"] = {{"vehicle_kg", options.vehicle_mass_kg},
                    {"core_kg", masses.core_mass_kg},
                    {"points_total_kg", masses.total_kg() - masses.core_mass_kg},
                    {"point_min_kg", *lightest},
                    {"point_max_kg", *heaviest},
                    {"sum_error_kg", masses.total_kg() - options.vehicle_mass_kg}};
  report["skin_method"] = deform::skinMethodName(skin.method());
  report["alpha"] = skin.alpha();
  report["k"] = skin.influences();
  report["dense"] = options.skin.k_nearest == 0;
  report["skin_bytes"] = skin.memoryBytes();
  report["weights_sum_max_error"] = sum_error;
  report["translation_error_max_m"] = translation_error;
  report["affine_reproduction_error_max_m"] = affine_error;
  report["weight_abs_max"] = spread.largest_abs_weight;
  report["weight_min"] = spread.smallest_weight;
  report["weights_negative_fraction"] = spread.negative_fraction;
  report["build_ms"] = {{"control_mesh", control_ms}, {"skin", skin_ms}};
  return report;
}

std::string formatMeshReport(const nlohmann::ordered_json& r) {
  std::ostringstream out;
  char line[256];
  auto v3 = [](const nlohmann::ordered_json& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.3f, %.3f, %.3f)", v[0].get<double>(), v[1].get<double>(),
                  v[2].get<double>());
    return std::string(buf);
  };
  out << "mesh               " << r["source"].get<std::string>() << "\n";
  std::snprintf(line, sizeof line, "render mesh        %zu vertices, %zu triangles, %zu wheels\n",
                r["vertices"].get<std::size_t>(), r["triangles"].get<std::size_t>(),
                r["wheels"].get<std::size_t>());
  out << line;
  out << "bounding box [m]   " << v3(r["bbox_min"]) << " .. " << v3(r["bbox_max"]) << ", size "
      << v3(r["bbox_size_m"]) << "\n";
  std::snprintf(line, sizeof line, "convex hull        %zu vertices, %.3f m^3, centre of mass %s\n",
                r["hull_vertices"].get<std::size_t>(), r["hull_volume_m3"].get<double>(),
                v3(r["centre_of_mass_m"]).c_str());
  out << line;
  std::snprintf(line, sizeof line, "control mesh       %zu points (%s), %zu triangles%s\n",
                r["control_points"].get<std::size_t>(), r["lod_method"].get<std::string>().c_str(),
                r["control_triangles"].get<std::size_t>(),
                r["mirror_symmetric"].get<bool>() ? ", mirror-symmetric" : "");
  out << line;
  std::snprintf(line, sizeof line,
                "spread [m]         largest gap %.3f (even spacing %.3f), edges %.3f .. %.3f\n",
                r["largest_gap_m"].get<double>(), r["even_gap_m"].get<double>(),
                r["shortest_edge_m"].get<double>(), r["longest_edge_m"].get<double>());
  out << line;
  std::snprintf(line, sizeof line,
                "fit                %.3f m^3 enclosed, hull vertices at most %.3f m outside\n",
                r["control_volume_m3"].get<double>(), r["hull_shortfall_m"].get<double>());
  out << line;
  const auto& m = r["mass"];
  std::snprintf(line, sizeof line,
                "masses [kg]        vehicle %.1f = core %.1f + points %.1f (each %.3f .. %.3f)\n",
                m["vehicle_kg"].get<double>(), m["core_kg"].get<double>(), m["points_total_kg"].get<double>(),
                m["point_min_kg"].get<double>(), m["point_max_kg"].get<double>());
  out << line;
  std::snprintf(line, sizeof line, "embedding          %s, alpha %.2f, %s %zu, %.1f MB of weights\n",
                r["skin_method"].get<std::string>().c_str(), r["alpha"].get<double>(),
                r["dense"].get<bool>() ? "dense over" : "K =", r["k"].get<std::size_t>(),
                static_cast<double>(r["skin_bytes"].get<std::size_t>()) / 1e6);
  out << line;
  std::snprintf(line, sizeof line,
                "checks             max |sum phi - 1| = %.2e, max translation error = %.2e m\n",
                r["weights_sum_max_error"].get<double>(), r["translation_error_max_m"].get<double>());
  out << line;
  std::snprintf(
      line, sizeof line,
      "                   max affine error = %.2e m (crash-sized rotation, stretch, shear, shift)\n",
      r["affine_reproduction_error_max_m"].get<double>());
  out << line;
  std::snprintf(line, sizeof line, "weights            max |w| = %.3f, min w = %.3f, %.1f %% negative\n",
                r["weight_abs_max"].get<double>(), r["weight_min"].get<double>(),
                100.0 * r["weights_negative_fraction"].get<double>());
  out << line;
  std::snprintf(line, sizeof line, "build [ms]         control mesh %.1f, skin %.1f\n",
                r["build_ms"]["control_mesh"].get<double>(), r["build_ms"]["skin"].get<double>());
  out << line;
  return out.str();
}

}  // namespace sandbox
