#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <map>

#include "point_sets.hpp"

using deform::ControlMesh;

namespace {

/// Every edge is used once in each direction (closed, consistently wound) and every triangle faces
/// away from the centre of mass (outward). With `convex`, every point is on or inside every face plane;
/// otherwise (the even method flips edges across slight bends) within 3 % of the body's size.
void requireClosedOutward(const ControlMesh& mesh, bool convex) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) directed[{t[k], t[(k + 1) % 3]}]++;
  for (const auto& [e, uses] : directed) {
    REQUIRE(uses == 1);
    REQUIRE(directed.count({e.second, e.first}) == 1);
  }
  REQUIRE(mesh.edges.size() * 2 == directed.size());
  REQUIRE(mesh.volume_m3 > 0);
  double scale = 0;
  for (const auto& p : mesh.points_m) scale = std::max(scale, (p - mesh.centre_of_mass_m).norm());
  double worst_outside = 0, least_outward = 1e300;
  for (const auto& t : mesh.triangles) {
    const auto &a = mesh.points_m[t[0]], &b = mesh.points_m[t[1]], &c = mesh.points_m[t[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() == 0) continue;
    n.normalize();
    least_outward = std::min(least_outward, n.dot(a - mesh.centre_of_mass_m));
    for (const auto& p : mesh.points_m) worst_outside = std::max(worst_outside, n.dot(p - a));
  }
  REQUIRE(least_outward > 0);
  REQUIRE(worst_outside <= (convex ? 1e-9 : 0.03) * scale);
}

}  // namespace

TEST_CASE("hull of a unit cube with interior points is the cube", "[control_mesh]") {
  auto points = test_points::cloud(200);
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  ControlMesh hull = deform::convexHull(points);
  // Each square face is fanned from its centre (no arbitrary diagonal): 8 corners + 6 face centres.
  CHECK(hull.hull_vertex_count == 8);
  CHECK(hull.points_m.size() == 14);
  CHECK(hull.triangles.size() == 24);
  CHECK(hull.edges.size() == 36);
  CHECK(hull.volume_m3 == Approx(1.0).epsilon(1e-12));
  CHECK(hull.centre_of_mass_m.norm() < 1e-12);
  requireClosedOutward(hull, true);
}

TEST_CASE("each triangle's neighbour across each edge shares that edge, both ways", "[control_mesh]") {
  const ControlMesh mesh = deform::buildControlMesh(test_points::cloud(500), 120, "cloud");
  const std::vector<uint32_t> across = deform::triangleNeighbours(mesh.triangles);
  REQUIRE(across.size() == 3 * mesh.triangles.size());
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (uint32_t j = 0; j < 3; ++j) {
      const uint32_t o = across[3 * t + j];
      REQUIRE(o < mesh.triangles.size());  // a closed surface has no open edge
      CHECK(o != t);
      const uint32_t u = mesh.triangles[t][j], v = mesh.triangles[t][(j + 1) % 3];
      // The other triangle runs the edge the other way (outward winding), and points back to t across it.
      bool found = false;
      for (uint32_t k = 0; k < 3; ++k)
        if (mesh.triangles[o][k] == v && mesh.triangles[o][(k + 1) % 3] == u) {
          found = true;
          CHECK(across[3 * o + k] == t);
        }
      CHECK(found);
    }
  // An open edge has none.
  const std::vector<uint32_t> lone = deform::triangleNeighbours({{0, 1, 2}});
  CHECK(lone == std::vector<uint32_t>(3, UINT32_MAX));
}

TEST_CASE("control mesh hits the target count from 4 to 5000 points", "[control_mesh]") {
  const auto points = test_points::sphere(1500, {2.4, 0.9, 0.7});  // car-sized ellipsoid
  for (std::size_t target : {4u, 8u, 30u, 60u, 250u, 1000u, 1499u, 1500u, 2000u, 4000u, 5000u}) {
    CAPTURE(target);
    ControlMesh even = deform::buildControlMesh(points, target);
    CHECK(even.points_m.size() == target);
    CHECK(even.hull_vertex_count == 1500);
    requireClosedOutward(even, false);
    // The paper's reduction: within 5 %, strictly convex.
    ControlMesh reduced = deform::buildControlMesh(points, target, "ellipsoid", deform::LodMethod::Simplify);
    const double count = static_cast<double>(reduced.points_m.size());
    CHECK(std::abs(count - static_cast<double>(target)) <= 0.05 * static_cast<double>(target));
    requireClosedOutward(reduced, target <= 1500);
  }
}

TEST_CASE("the even method leaves no hole much larger than an even spacing; simplify does",
          "[control_mesh]") {
  // A car-like box with rounded ends: long flat sides where simplification keeps no points.
  auto points = test_points::sphere(3000, {2.4, 0.9, 0.7});
  for (auto& p : points) p = Eigen::Vector3d(std::clamp(p.x(), -1.8, 1.8) + 0.2 * p.x(), p.y(), p.z());
  for (std::size_t target : {60u, 250u, 1000u}) {
    CAPTURE(target);
    auto even = deform::buildControlMesh(points, target);
    auto simplified = deform::buildControlMesh(points, target, "box", deform::LodMethod::Simplify);
    auto even_stats = deform::controlMeshStats(even), simplified_stats = deform::controlMeshStats(simplified);
    const double even_spacing = std::sqrt(even_stats.surface_area_m2 / static_cast<double>(target));
    CAPTURE(even_stats.largest_gap_m, simplified_stats.largest_gap_m, even_spacing);
    CHECK(even_stats.largest_gap_m < 1.3 * even_spacing);
    CHECK(simplified_stats.largest_gap_m > even_stats.largest_gap_m);
  }
}

TEST_CASE("refined control points spread evenly: the largest gap shrinks as points are added",
          "[control_mesh]") {
  // A box has 8 hull vertices; every further point comes from longest-edge bisection.
  std::vector<Eigen::Vector3d> box;
  for (int i = 0; i < 8; ++i) box.emplace_back(i & 1 ? 2.4 : -2.4, i & 2 ? 0.9 : -0.9, i & 4 ? 1.4 : 0.0);
  double previous_gap = 1e9;
  for (std::size_t target : {8u, 60u, 250u, 1000u, 4000u}) {
    ControlMesh mesh = deform::buildControlMesh(box, target);
    CHECK(mesh.points_m.size() == target);
    auto stats = deform::controlMeshStats(mesh);
    CHECK(stats.largest_gap_m < previous_gap);
    CHECK(mesh.mirror_of.size() == target);  // the box is symmetric in y, and so is its control mesh
    // Bisection keeps the spread within a small factor of an ideal even spacing on the surface area.
    double area = 2 * (4.8 * 1.8 + 4.8 * 1.4 + 1.8 * 1.4);
    double ideal_gap = std::sqrt(area / static_cast<double>(target) * 2.0 / std::sqrt(3.0));
    if (target >= 60) CHECK(stats.largest_gap_m < 1.5 * ideal_gap);
    previous_gap = stats.largest_gap_m;
    requireClosedOutward(mesh, false);
    CHECK(mesh.volume_m3 == Approx(4.8 * 1.8 * 1.4).epsilon(1e-9));
  }
}

TEST_CASE("the shortfall is the distance of a point outside the control surface, and shrinks with N",
          "[control_mesh]") {
  // A box's 8 corners are its whole hull: nothing falls short of it, and a point 0.3 m off the middle of
  // its front face, or 0.3 m out past a corner along the diagonal, is that far outside.
  std::vector<Eigen::Vector3d> box;
  for (int i = 0; i < 8; ++i) box.emplace_back(i & 1 ? 2.4 : -2.4, i & 2 ? 0.9 : -0.9, i & 4 ? 1.4 : 0.0);
  const ControlMesh hull = deform::buildControlMesh(box, 8);
  CHECK(deform::controlSurfaceShortfall_m(hull, box) == Approx(0).margin(1e-12));
  CHECK(deform::controlSurfaceShortfall_m(hull, {{2.7, 0.1, 0.7}, {0, 0, 0.7}}) ==
        Approx(0.3).epsilon(1e-12));
  const Eigen::Vector3d corner(2.4, 0.9, 1.4), out = corner + 0.3 * Eigen::Vector3d(1, 1, 1).normalized();
  CHECK(deform::controlSurfaceShortfall_m(hull, {out}) == Approx(0.3).epsilon(1e-12));
  // A rounded body: its coarse control surfaces cut its curves, less the more points they have.
  const auto sphere = test_points::sphere(3000, {2.4, 0.9, 0.7});
  double previous_m = 1e9;
  for (std::size_t target : {30u, 120u, 500u}) {
    CAPTURE(target);
    const double shortfall_m =
        deform::controlSurfaceShortfall_m(deform::buildControlMesh(sphere, target), sphere);
    CHECK(shortfall_m > 0);
    CHECK(shortfall_m < previous_m);
    previous_m = shortfall_m;
  }
}

TEST_CASE("control mesh is deterministic", "[control_mesh]") {
  const auto points = test_points::cloud(3000, 7);
  for (auto method : {deform::LodMethod::Even, deform::LodMethod::Simplify}) {
    for (std::size_t target : {30u, 2000u}) {
      ControlMesh a = deform::buildControlMesh(points, target, "cloud", method);
      ControlMesh b = deform::buildControlMesh(points, target, "cloud", method);
      REQUIRE(a.points_m == b.points_m);
      REQUIRE(a.triangles == b.triangles);
    }
  }
}

TEST_CASE("reduced control points lie on the original hull", "[control_mesh]") {
  const auto points = test_points::cloud(2000, 3);
  ControlMesh hull = deform::convexHull(points);
  ControlMesh reduced = deform::buildControlMesh(points, 20, "cloud", deform::LodMethod::Simplify);
  // Every reduced point is on the original hull's surface: inside or on every face plane, on one.
  for (const auto& p : reduced.points_m) {
    double highest = -1e300;
    for (const auto& t : hull.triangles) {
      const auto &a = hull.points_m[t[0]], &b = hull.points_m[t[1]], &c = hull.points_m[t[2]];
      highest = std::max(highest, (b - a).cross(c - a).normalized().dot(p - a));
    }
    CHECK(std::abs(highest) < 1e-9);
  }
  CHECK(reduced.volume_m3 < hull.volume_m3);
  CHECK(reduced.volume_m3 > 0.5 * hull.volume_m3);
}

TEST_CASE("degenerate point sets are refused with a message", "[control_mesh]") {
  using Catch::Matchers::Contains;
  std::vector<Eigen::Vector3d> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  CHECK_THROWS_WITH(deform::convexHull(three, "tri.obj"), Contains("tri.obj") && Contains("at least 4"));
  std::vector<Eigen::Vector3d> duplicates(50, Eigen::Vector3d(1, 2, 3));
  CHECK_THROWS_WITH(deform::convexHull(duplicates, "dup"), Contains("at least 4"));
  std::vector<Eigen::Vector3d> line, flat;
  for (int i = 0; i < 20; ++i) line.emplace_back(i, 2.0 * i, -i);
  for (int i = 0; i < 20; ++i) flat.emplace_back(i % 5, i / 5, 0.0);
  CHECK_THROWS_WITH(deform::convexHull(line, "line"), Contains("collinear"));
  CHECK_THROWS_WITH(deform::convexHull(flat, "flat"), Contains("flat"));
  std::vector<Eigen::Vector3d> nan = test_points::cloud(10);
  nan[3].x() = std::nan("");
  CHECK_THROWS_WITH(deform::convexHull(nan, "nan"), Contains("non-finite"));
  CHECK_THROWS_AS(deform::buildControlMesh(test_points::cloud(100), 3), deform::InputError);
  // The smallest valid input: a tetrahedron.
  std::vector<Eigen::Vector3d> tet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ControlMesh mesh = deform::buildControlMesh(tet, 4);
  CHECK(mesh.points_m.size() == 4);
  CHECK(mesh.volume_m3 == Approx(1.0 / 6.0));
}

TEST_CASE("a hull far from the origin keeps its precision", "[control_mesh]") {
  auto points = test_points::sphere(400, {2.4, 0.9, 0.7});
  ControlMesh near = deform::buildControlMesh(points, 60);
  const Eigen::Vector3d offset(1e5, -1e5, 50);
  for (auto& p : points) p += offset;
  ControlMesh far = deform::buildControlMesh(points, 60);
  REQUIRE(far.points_m.size() == near.points_m.size());
  CHECK(far.volume_m3 == Approx(near.volume_m3).epsilon(1e-6));
  CHECK((far.centre_of_mass_m - offset - near.centre_of_mass_m).norm() < 1e-6);
}

TEST_CASE("points in flat faces go into the same triangles whether found by the grid or among all",
          "[control_mesh]") {
  // triangulateOnConvexSurface's two ways of finding the triangle a dropped point lies in: the grid's
  // near list (the default) and the scan of every triangle (the reference) give the same surface, to the
  // bit. Inputs with many points inside flat faces: a box's faces sampled on a lattice, a sphere with a
  // flattened belt, and the even control meshes of the built-in sedan (whose flat sides and roof
  // are where the hull drops the most points).
  std::vector<std::vector<Eigen::Vector3d>> sets;
  std::vector<Eigen::Vector3d> box;
  for (int i = 0; i <= 12; ++i)
    for (int j = 0; j <= 8; ++j) {
      const double u = -2.4 + 0.4 * i, v = -0.9 + 0.225 * j, w = 1.4 * j / 8.0;
      box.insert(box.end(), {{u, v, 0}, {u, v, 1.4}, {u, -0.9, w}, {u, 0.9, w}, {-2.4, v, w}, {2.4, v, w}});
    }
  sets.push_back(box);
  auto belt = test_points::sphere(2000, {2.4, 0.9, 0.7});
  for (auto& p : belt) p.z() = std::clamp(p.z(), -0.4, 0.4);
  sets.push_back(belt);
  std::vector<Eigen::Vector3d> car;
  for (const auto& p : deform::makeSedan(4000).body.positions_m) car.push_back(p.cast<double>());
  for (std::size_t target : {60u, 1000u}) sets.push_back(deform::buildControlMesh(car, target).points_m);
  for (const auto& points : sets) {
    CAPTURE(points.size());
    const ControlMesh by_cells = deform::triangulateOnConvexSurface(points, "test", true);
    const ControlMesh reference = deform::triangulateOnConvexSurface(points, "test", false);
    CHECK(by_cells.points_m.size() >
          deform::convexHull(points, "test", deform::FacetSplit::Diagonals).points_m.size());
    CHECK(by_cells.points_m == reference.points_m);
    CHECK(by_cells.triangles == reference.triangles);
  }
}

TEST_CASE("farthest-point sampling by cells and heaps takes the reference's points, in its order",
          "[control_mesh]") {
  // Candidates as the even method makes them: on a surface, some flagged as corners, mirrored in y with
  // a few on the plane; and a lattice, whose many equal distances test the ties (lowest index first).
  std::vector<Eigen::Vector3d> half = test_points::sphere(1500, {2.4, 0.9, 0.7});
  std::vector<Eigen::Vector3d> mirrored;
  for (const auto& p : half)
    if (p.y() > 0.05)
      mirrored.insert(mirrored.end(), {p, {p.x(), -p.y(), p.z()}});
    else if (p.y() > -0.05)
      mirrored.emplace_back(p.x(), 0.0, p.z());
  std::vector<uint32_t> mirror_of(mirrored.size());
  for (uint32_t i = 0; i < mirrored.size(); ++i)
    mirror_of[i] = mirrored[i].y() > 0 ? i + 1 : mirrored[i].y() < 0 ? i - 1 : i;
  std::vector<char> corners(mirrored.size(), 0);
  for (std::size_t i = 0; i < mirrored.size(); i += 7) {
    corners[i] = 1;
    corners[mirror_of[i]] = 1;
  }
  std::vector<Eigen::Vector3d> lattice;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 3; ++k) lattice.emplace_back(0.25 * i, 0.25 * j, 0.25 * k);
  const std::vector<char> no_corners(lattice.size(), 0), every_fifth = [&] {
    std::vector<char> c(lattice.size(), 0);
    for (std::size_t i = 0; i < c.size(); i += 5) c[i] = 1;
    return c;
  }();
  for (std::size_t count : {7u, 60u, 301u, 1200u}) {
    CAPTURE(count);
    const Eigen::Vector3d centre(0.1, 0, 0.05);
    CHECK(deform::farthestPoints(mirrored, count, centre, mirror_of, corners, 0.3, true) ==
          deform::farthestPoints(mirrored, count, centre, mirror_of, corners, 0.3, false));
    CHECK(deform::farthestPoints(lattice, count, centre, {}, no_corners, 0.0, true) ==
          deform::farthestPoints(lattice, count, centre, {}, no_corners, 0.0, false));
    CHECK(deform::farthestPoints(lattice, count, centre, {}, every_fifth, 0.6, true) ==
          deform::farthestPoints(lattice, count, centre, {}, every_fifth, 0.6, false));
  }
}
