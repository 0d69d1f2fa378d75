#include "grid/bench_grid.hpp"

#include "elapsed.hpp"

#include "baselines/bullet_soft_body.hpp"
#include "grid/full_resolution.hpp"
#include "step_cost.hpp"

#include <deform/body_settings.hpp>
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/masses.hpp>
#include <deform/skin.hpp>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>

namespace sandbox {
namespace {

constexpr double kMass_kg = 1500;

// The balanced solver, one deformation step per 60 Hz frame.
StepCostOptions frameStep(std::size_t points) {
  StepCostOptions o;
  o.substeps = 4;
  o.iterations = 2;
  o.dt_s = 1.0 / 60;
  // Large bodies take long per step: fewer repetitions, still a median.
  o.warmup = points > 200000 ? 1 : points > 20000 ? 2 : 10;
  o.steps = points > 200000 ? 1 : points > 20000 ? 3 : 50;
  return o;
}

// Median time of the full embedding pass (every vertex, control points displaced by 1 cm) [ms].
double embedPass_ms(const deform::Skin& skin, const std::vector<Eigen::Vector3f>& rest_m, unsigned threads) {
  const std::vector<Eigen::Vector3d> displacement(skin.controlPointCount(),
                                                  Eigen::Vector3d(0.01, 0.0, -0.005));
  std::vector<Eigen::Vector3f> out(rest_m.size());
  const int repetitions = rest_m.size() > 1000000 ? 5 : 11;
  std::vector<double> ms;
  skin.deform(rest_m.data(), displacement.data(), out.data(), threads);  // warm the caches
  for (int r = 0; r < repetitions; ++r) {
    const auto start = Clock::now();
    skin.deform(rest_m.data(), displacement.data(), out.data(), threads);
    ms.push_back(msSince(start));
  }
  std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(ms.size() / 2), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace

deform::Mesh asMesh(const deform::ControlMesh& control) {
  deform::Mesh mesh;
  for (const auto& p : control.points_m) mesh.positions_m.push_back(p.cast<float>());
  mesh.triangles = control.triangles;
  return mesh;
}

namespace {

deform::Mesh crashControlMesh() {
  const deform::Mesh body = deform::makeSedan(20000).body;
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : body.positions_m) points.push_back(p.cast<double>());
  return asMesh(deform::buildControlMesh(points, 60, "builtin:sedan"));
}

}  // namespace

baselines::SoftBodyCrash bulletCrash(double speed_kmh) {
  return baselines::bulletWallCrash(crashControlMesh(), kMass_kg, speed_kmh, 1.2, 500);
}

std::vector<baselines::SoftBodyCrash> bulletCrashes(const GridOptions& options) {
  const deform::Mesh control = crashControlMesh();
  std::vector<baselines::SoftBodyCrash> out;
  for (double kmh : options.bullet_crash_speeds_kmh)
    out.push_back(baselines::bulletWallCrash(control, kMass_kg, kmh, 1.2, 500));
  return out;
}

GridOptions GridOptions::quick() {
  GridOptions o;
  o.vertices = {10000, 100000};
  o.control_points = {8, 60, 1000};
  o.full_resolution_max_vertices = 100000;
  o.bullet_max_vertices = 10000;
  return o;
}

std::vector<GridRow> runBenchGridResolution(const GridOptions& options, std::size_t vertices,
                                            bool first_resolution, std::map<std::size_t, double>& step_ms_of,
                                            const std::function<void(const GridRow&)>& on_row) {
  std::vector<GridRow> rows;
  const auto emit = [&](const GridRow& row) {
    rows.push_back(row);
    if (on_row) on_row(row);
  };
  const deform::Mesh body = deform::makeSedan(vertices).body;
  std::vector<Eigen::Vector3d> points;
  points.reserve(body.positions_m.size());
  for (const auto& p : body.positions_m) points.push_back(p.cast<double>());
  auto start = Clock::now();
  const deform::ControlMesh hull = deform::convexHull(points, "builtin:sedan");
  const double hull_ms = msSince(start);

  for (const std::size_t n : options.control_points) {
    GridRow row;
    row.method = "skin K=8";
    row.vertices = body.positions_m.size();
    row.hull_ms = hull_ms;
    start = Clock::now();
    const deform::ControlMesh mesh = deform::buildControlMesh(hull.points_m, n, "builtin:sedan");
    row.lod_ms = msSince(start);
    row.control_points = mesh.points_m.size();
    start = Clock::now();
    const auto settings = std::make_shared<const deform::BodySettings>(
        deform::createBodySettings(mesh, deform::distributeMass(mesh, kMass_kg), deform::BodyDescription{}));
    row.body_ms = msSince(start);
    row.constraints = settings->constraintCount();
    if (!step_ms_of.count(n))
      step_ms_of[n] = measureStepCost(settings, frameStep(row.control_points)).us_per_step * 1e-3;
    row.step_ms = step_ms_of[n];

    for (const std::size_t k : {std::size_t{8}, std::size_t{0}}) {
      GridRow cell = row;
      if (k == 0) {
        cell.method = "skin dense";
        const std::size_t bytes = row.vertices * row.control_points * (sizeof(float) + sizeof(uint16_t));
        if (bytes > options.dense_budget_bytes) continue;  // would not fit: not measured
      }
      deform::SkinOptions skin_options;
      skin_options.k_nearest = k;
      skin_options.threads = options.threads;
      start = Clock::now();
      const deform::Skin skin = deform::Skin::build(body.positions_m, mesh.points_m, skin_options);
      cell.skin_ms = msSince(start);
      cell.skin_bytes = skin.memoryBytes();
      cell.embed_ms = embedPass_ms(skin, body.positions_m, options.threads);
      emit(cell);
    }
    if (first_resolution) {
      // Bullet's soft body on the same control mesh, as its deformation model (the skin's embedding
      // would come on top).
      const baselines::SoftBodyCost bullet = baselines::bulletSoftBodyCost(asMesh(mesh), kMass_kg, 60, 4);
      GridRow b = row;
      b.method = "Bullet soft body (control mesh)";
      b.constraints = bullet.links;
      b.body_ms = bullet.build_ms;
      b.step_ms = bullet.ms_per_frame;
      b.note = bullet.finite ? "" : "not finite";
      emit(b);
    }
  }
  if (vertices <= options.full_resolution_max_vertices)
    emit(fullResolutionRow(body, kMass_kg, frameStep(vertices)));
  if (vertices <= options.bullet_max_vertices) {
    const baselines::SoftBodyCost bullet =
        baselines::bulletSoftBodyCost(body, kMass_kg, vertices > 20000 ? 5 : 30, 4);
    GridRow b;
    b.method = "Bullet soft body (render mesh)";
    b.vertices = body.positions_m.size();
    b.control_points = bullet.nodes;
    b.constraints = bullet.links;
    b.body_ms = bullet.build_ms;
    b.step_ms = bullet.ms_per_frame;
    b.note = bullet.finite ? "" : "not finite";
    emit(b);
  }
  return rows;
}

std::vector<GridRow> runBenchGrid(const GridOptions& options,
                                  const std::function<void(const GridRow&)>& on_row) {
  std::vector<GridRow> rows;
  std::map<std::size_t, double> step_ms_of;  // the step does not depend on the render mesh
  for (const std::size_t vertices : options.vertices) {
    for (GridRow& row :
         runBenchGridResolution(options, vertices, vertices == options.vertices.front(), step_ms_of, on_row))
      rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace sandbox
