// The crash metrics' tunnelling test (vehicle/src/segment_meets.hpp): a straight path through a thin wall
// or post is found, one past its end or grazing its surface is not.
#include "segment_meets.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace {

// A wall 0.14 m thick, 1.05 m wide and 0.96 m high, turned 145 degrees about the vertical (random scene
// 10_13's), its foot on the ground.
vehicle::ObstacleShape thinWall() {
  vehicle::ObstacleShape wall;
  wall.type = vehicle::ShapeType::Box;
  wall.centre_m = {0.165, 5.717, 0.48};
  const double yaw = 145.1 * M_PI / 180.0;
  wall.axes << std::cos(yaw), -std::sin(yaw), 0, std::sin(yaw), std::cos(yaw), 0, 0, 0, 1;
  wall.half_extents_m = {0.07, 0.525, 0.48};
  return wall;
}

// A point at (thickness, width, height) in the wall's own axes.
Eigen::Vector3d onWall(const vehicle::ObstacleShape& wall, double across, double along, double up) {
  return wall.centre_m + wall.axes * Eigen::Vector3d(across, along, up);
}

}  // namespace

TEST_CASE("a path through a thin wall is found, one beside it or along its face is not", "[tunnel]") {
  const vehicle::ObstacleShape wall = thinWall();
  // Straight through, in one step much longer than the wall is thick.
  CHECK(vehicle::segmentMeets(wall, onWall(wall, -0.2, 0.1, 0.2), onWall(wall, 0.2, 0.1, 0.2)));
  // Into it, ending inside.
  CHECK(vehicle::segmentMeets(wall, onWall(wall, -0.2, 0.1, 0.2), onWall(wall, 0.01, 0.1, 0.2)));
  // Across its plane 1 cm beyond its end, above it, and along its face 1 mm off it.
  CHECK_FALSE(vehicle::segmentMeets(wall, onWall(wall, -0.2, 0.535, 0.2), onWall(wall, 0.2, 0.535, 0.2)));
  CHECK_FALSE(vehicle::segmentMeets(wall, onWall(wall, -0.2, 0.0, 0.97), onWall(wall, 0.2, 0.0, 0.97)));
  CHECK_FALSE(vehicle::segmentMeets(wall, onWall(wall, 0.071, 2.0, 0.2), onWall(wall, 0.071, -2.0, 0.2)));
  // The chord the tunnelling test took before (scene 10_13): from where the car hit the wall's end to
  // where it slid along the far face, it passes through the wall; the car's steps went around it.
  CHECK(vehicle::segmentMeets(wall, {0.2436, 2.9075, 0.6878}, {-0.3951, 6.7248, 0.7153}));
  CHECK_FALSE(vehicle::segmentMeets(wall, onWall(wall, -1.08, 1.94, 0.2), onWall(wall, 0.55, 1.11, 0.2)));
}

TEST_CASE("a path through a 3 cm post is found however near its rim", "[tunnel]") {
  vehicle::ObstacleShape post;
  post.type = vehicle::ShapeType::Cylinder;
  post.a_m = {0, 0, 0};
  post.b_m = {0, 0, 1.5};
  post.radius_m = 0.03;
  for (const double offset : {0.0, 0.02, 0.029})
    CHECK(vehicle::segmentMeets(post, {-0.39, offset, 0.5}, {0.41, offset, 0.5}));  // no sample at x = 0
  CHECK_FALSE(vehicle::segmentMeets(post, {-0.4, 0.031, 0.5}, {0.4, 0.031, 0.5}));
  CHECK_FALSE(vehicle::segmentMeets(post, {-0.4, 0.0, 1.6}, {0.4, 0.0, 1.6}));  // over its top
  post.type = vehicle::ShapeType::Capsule;
  CHECK(vehicle::segmentMeets(post, {-0.4, 0.0, 0.5}, {0.4, 0.0, 0.5}));
}
