// Render vertices projected out of obstacles: onto the surface (within 1e-6 m, outside) for a box, a
// capsule (a post) and a convex hull; a thin post never pulls the skin through to its far side; the
// grid finds every vertex near an obstacle.
#include <deform/surface_projection.hpp>

#include <catch2/catch.hpp>
#include <cmath>

namespace {

// Points on a lattice filling the cube [-h, h]^3 around `centre`.
std::vector<Eigen::Vector3d> lattice(const Eigen::Vector3d& centre, double h_m, int per_side) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < per_side; ++i)
    for (int j = 0; j < per_side; ++j)
      for (int k = 0; k < per_side; ++k)
        points.push_back(centre +
                         h_m * (2.0 * Eigen::Vector3d(i, j, k) / (per_side - 1) - Eigen::Vector3d::Ones()));
  return points;
}

// Every lattice point inside `shape` ends outside it and within 1e-6 m of its surface, on the side of
// `interior`; every point outside stays bit for bit where it was.
void requireProjectedOnto(const deform::ContactShape& shape, const Eigen::Vector3d& interior_m,
                          const Eigen::Vector3d& centre_m, double h_m) {
  std::size_t moved = 0;
  for (const Eigen::Vector3d& start : lattice(centre_m, h_m, 15)) {
    deform::Penetration before;
    const bool was_inside = deform::penetration(shape, start, before) && before.depth_m > 0;
    Eigen::Vector3d x = start;
    REQUIRE(deform::projectOutOf(shape, interior_m, x) == was_inside);
    if (!was_inside) {
      REQUIRE(x == start);
      continue;
    }
    ++moved;
    deform::Penetration after;
    CAPTURE(start.transpose(), x.transpose());
    REQUIRE(deform::penetration(shape, x, after, 1e-6));  // within 1e-6 m of the surface
    CHECK(after.depth_m <= 0);                            // and outside
    CHECK(after.depth_m >= -1e-6);
    // Stored as a float (a render position) it is still outside.
    deform::Penetration stored;
    const Eigen::Vector3d as_float = x.cast<float>().cast<double>();
    CHECK(!(deform::penetration(shape, as_float, stored) && stored.depth_m > 0));
  }
  CHECK(moved > 50);
}

}  // namespace

TEST_CASE("vertices inside a box, a post, a bollard and a convex hull are projected onto the surface",
          "[surface_projection]") {
  const Eigen::Vector3d interior(-3.0, 0.2, 0.5);  // the car's middle, outside the obstacles
  SECTION("box (a wall), turned") {
    deform::BoxShape wall;
    wall.centre_m = {0.4, 0.1, 0.6};
    wall.axes = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    wall.half_extents_m = {0.3, 1.0, 0.7};
    requireProjectedOnto(wall, interior, wall.centre_m, 1.2);
  }
  SECTION("capsule (a post or a tree)") {
    const deform::CapsuleShape post{{0.2, 0.0, -1.0}, {0.2, 0.0, 2.0}, 0.15};
    requireProjectedOnto(post, interior, {0.2, 0.0, 0.5}, 0.3);
  }
  SECTION("cylinder with flat ends (a bollard, as the scenes' posts are met)") {
    const deform::CylinderShape bollard{{0.2, 0.0, -1.0}, {0.2, 0.0, 0.9}, 0.12, Eigen::Vector3d::Zero()};
    requireProjectedOnto(bollard, interior, {0.2, 0.0, 0.5}, 0.3);
    requireProjectedOnto(bollard, interior, {0.2, 0.0, 0.85}, 0.3);  // about its flat top
  }
  SECTION("convex hull (another car's corner)") {
    const deform::ConvexPoints hull({{0.0, -0.5, 0.2},
                                     {0.8, -0.6, 0.1},
                                     {0.9, 0.7, 0.3},
                                     {0.1, 0.5, 0.0},
                                     {0.3, 0.0, 1.1},
                                     {0.6, 0.1, -0.4},
                                     {0.2, -0.2, 0.9}});
    requireProjectedOnto(hull.shape(), interior, {0.45, 0.0, 0.35}, 0.8);
  }
}

TEST_CASE("a thin post in a sheet of vertices does not pull them through to its far side",
          "[surface_projection]") {
  // A sheet of vertices (the car's front, x = 0, spaced 5 mm) with the car behind it (-x), and a post of
  // 0.05 m radius whose axis has gone 2 cm past the sheet: the vertices inside it are beyond its axis,
  // where the shortest way out is the far side.
  const double axis_x = -0.02;
  const deform::CapsuleShape post{{axis_x, 0.0, -2.0}, {axis_x, 0.0, 2.0}, 0.05};
  const Eigen::Vector3d interior(-1.5, 0.0, 0.0);
  std::size_t moved = 0;
  for (int i = -40; i <= 40; ++i)
    for (int k = -10; k <= 10; ++k) {
      Eigen::Vector3d x(0.0, 0.005 * i, 0.005 * k);
      if (!deform::projectOutOf(post, interior, x)) continue;
      ++moved;
      CAPTURE(x.transpose());
      CHECK(x.x() < axis_x);  // on the car's side of the post
      const double from_axis = Eigen::Vector2d(x.x() - axis_x, x.y()).norm();
      CHECK(from_axis >= 0.05);
      CHECK(from_axis < 0.05 + 1e-6);
    }
  CHECK(moved > 100);
}

TEST_CASE("the vertex grid finds every vertex near an obstacle and few others", "[surface_projection]") {
  std::vector<Eigen::Vector3f> rest;
  for (const Eigen::Vector3d& p : lattice({0, 0, 0}, 1.0, 30)) rest.push_back(p.cast<float>());
  const deform::VertexGrid grid(rest);
  const deform::BoxShape box{{0.8, 0.0, 0.0}, Eigen::Matrix3d::Identity(), {0.1, 0.2, 0.2}};
  const double reach_m = 0.05;
  std::vector<uint32_t> near;
  deform::verticesNear(box, grid, reach_m, near);
  std::size_t within = 0;
  for (std::size_t v = 0; v < rest.size(); ++v) {
    deform::Penetration p;
    if (!deform::penetration(box, rest[v].cast<double>(), p, reach_m)) continue;
    ++within;
    CHECK(std::find(near.begin(), near.end(), static_cast<uint32_t>(v)) != near.end());
  }
  CHECK(within > 0);
  CHECK(near.size() < rest.size() / 8);  // the box's neighbourhood, not the mesh

  // The ground: only the vertices within reach of z = -0.9 from above.
  near.clear();
  deform::verticesNear(deform::HalfSpaceShape{{0, 0, 1}, -0.9}, grid, reach_m, near);
  for (std::size_t v = 0; v < rest.size(); ++v)
    if (rest[v].z() < -0.9 + reach_m)
      CHECK(std::find(near.begin(), near.end(), static_cast<uint32_t>(v)) != near.end());
  CHECK(near.size() < rest.size() / 4);
}
