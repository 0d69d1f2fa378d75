// bench grid: what its rows must say about the method against the baselines, on a small grid.
#include <baselines/bullet_soft_body.hpp>
#include <grid/bench_grid.hpp>

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>

#include <catch2/catch.hpp>

namespace {

const sandbox::GridRow& find(const std::vector<sandbox::GridRow>& rows, const std::string& method,
                             std::size_t points) {
  for (const auto& r : rows) {
    if (r.method == method && (points == 0 || r.control_points == points)) return r;
  }
  FAIL("no row " << method << " with " << points << " points");
  return rows.front();
}

}  // namespace

TEST_CASE("bench grid: sparse skin is smaller than dense, full resolution simulates every vertex",
          "[bench]") {
  sandbox::GridOptions options;
  options.vertices = {3000};
  options.control_points = {30, 120};
  options.full_resolution_max_vertices = 3000;
  options.bullet_max_vertices = 3000;
  const auto rows = sandbox::runBenchGrid(options);
  const auto& sparse = find(rows, "skin K=8", 120);
  const auto& dense = find(rows, "skin dense", 120);
  // K = 8 slots against 120 per vertex: the weights shrink by the same ratio.
  CHECK(static_cast<double>(dense.skin_bytes) / static_cast<double>(sparse.skin_bytes) ==
        Approx(120.0 / 8.0).epsilon(0.02));
  const auto& full = find(rows, "full-resolution XPBD", 0);
  CHECK(full.control_points == full.vertices);
  CHECK(full.constraints > 3 * sparse.constraints);
  // Simulating every vertex costs more per frame than the control mesh plus the embedding.
  CHECK(full.step_ms > sparse.frame_ms());
  const auto& bullet = find(rows, "Bullet soft body (render mesh)", 0);
  CHECK(bullet.control_points == bullet.vertices);
  for (const auto& r : rows) {
    INFO(r.method << " " << r.control_points);
    CHECK(r.step_ms > 0);
    CHECK(r.note.empty());
  }
}

TEST_CASE("Bullet baseline: one link per edge of a closed mesh, and it rests on the ground",
          "[bench][bullet]") {
  const deform::Mesh sedan = deform::makeSedan(2000).body;
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : sedan.positions_m) points.push_back(p.cast<double>());
  const deform::Mesh control = sandbox::asMesh(deform::buildControlMesh(points, 60, "builtin:sedan"));
  const auto cost = sandbox::baselines::bulletSoftBodyCost(control, 1500, 120, 4);
  CHECK(cost.nodes == control.positions_m.size());
  CHECK(cost.faces == control.triangles.size());
  // Euler: V - E + F = 2 for a closed genus-0 surface.
  CHECK(static_cast<long>(cost.nodes) - static_cast<long>(cost.links) + static_cast<long>(cost.faces) == 2);
  CHECK(cost.finite);
}

TEST_CASE("Bullet baseline: the wall stops the soft body at 56 km/h", "[bench][bullet]") {
  const deform::Mesh sedan = deform::makeSedan(2000).body;
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : sedan.positions_m) points.push_back(p.cast<double>());
  const deform::Mesh control = sandbox::asMesh(deform::buildControlMesh(points, 60, "builtin:sedan"));
  const auto crash = sandbox::baselines::bulletWallCrash(control, 1500, 56, 1.2, 500);
  INFO(crash.verdict);
  CHECK(crash.finite);
  CHECK_FALSE(crash.tunnelled);
  CHECK(crash.max_extent_growth < 1.0);
}
