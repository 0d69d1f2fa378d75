#include "stress/random_obstacles.hpp"

#include "stress/stress_support.hpp"

#include <algorithm>
#include <cstdio>
#include <numbers>

namespace sandbox {
namespace {

using stress_support::kDegree;

// The built-in can's radius at mesh_scale 1 (deform/io/builtin_shapes.cpp) [m].
constexpr double kCanRadius_m = 0.033;

std::string twoDecimals(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

// Free (a mass) or static (mass 0, what a box or mesh obstacle takes for fixed).
double freeMass_kg(RandomDraws& draws, double lightest_kg, double heaviest_kg) {
  return draws.chance(0.25) ? 0.0 : draws.logUniform(lightest_kg, heaviest_kg, 0.1);
}

ObstacleShape wall(RandomDraws& draws) {
  const Eigen::Vector3d size_m(draws.logUniform(0.1, 2, 0.01), draws.logUniform(0.5, 12, 0.01),
                               draws.logUniform(0.2, 3, 0.01));
  ObstacleShape s{"wall", {{"type", "wall"}, {"size_m", {size_m.x(), size_m.y(), size_m.z()}}}};
  s.half_size_m = size_m.head<2>() / 2;
  s.yaw_to_path_deg = draws.uniform(-60, 60, 0.1);
  s.centre_height_m = size_m.z() / 2;
  return s;
}

ObstacleShape box(RandomDraws& draws) {
  const Eigen::Vector3d size_m(draws.logUniform(0.2, 3, 0.01), draws.logUniform(0.2, 3, 0.01),
                               draws.logUniform(0.2, 3, 0.01));
  const double mass_kg = freeMass_kg(draws, 5, 5000);
  ObstacleShape s{mass_kg > 0 ? "free box" : "box",
                  {{"type", "box"}, {"size_m", {size_m.x(), size_m.y(), size_m.z()}}, {"mass_kg", mass_kg}}};
  s.half_size_m = size_m.head<2>() / 2;
  s.yaw_to_path_deg = draws.uniform(-180, 180, 0.1);
  s.centre_height_m = size_m.z() / 2;
  return s;
}

ObstacleShape post(RandomDraws& draws) {
  const double radius_m = draws.logUniform(0.03, 0.5, 0.001);
  const bool capsule = draws.chance(0.25);
  // A capsule's rounded ends need a height past its diameter (the world refuses one that is not).
  const double lowest_m = capsule ? std::max(0.3, 2 * radius_m + 0.02) : 0.3;
  ObstacleShape s{capsule ? "capsule post" : "post",
                  {{"type", "post"},
                   {"radius_m", radius_m},
                   {"height_m", draws.logUniform(lowest_m, 3, 0.01)},
                   {"shape", capsule ? "capsule" : "cylinder"}}};
  s.half_size_m = {radius_m, radius_m};
  return s;
}

ObstacleShape vegetation(RandomDraws& draws) {
  const double radius_m = draws.logUniform(0.02, 0.5, 0.001);
  ObstacleShape s{"tree",
                  {{"type", "vegetation"},
                   {"radius_m", radius_m},
                   {"height_m", draws.logUniform(0.5, 8, 0.01)},
                   {"mass_kg", draws.logUniform(1, 3000, 0.1)}}};
  s.half_size_m = {radius_m, radius_m};
  return s;
}

ObstacleShape ramp(RandomDraws& draws) {
  const double length_m = draws.logUniform(1, 6, 0.01), width_m = draws.logUniform(0.5, 4, 0.01);
  ObstacleShape s{"ramp",
                  {{"type", "ramp"},
                   {"length_m", length_m},
                   {"width_m", width_m},
                   {"height_m", draws.logUniform(0.1, 1.5, 0.01)}}};
  s.half_size_m = {length_m / 2, width_m / 2};
  s.yaw_to_path_deg = draws.uniform(-20, 20, 0.1);
  s.ramp_length_m = length_m;
  return s;
}

// A convex mesh: a built-in box (its centre at its position) or the built-in can scaled to a drum (its
// base at its position).
ObstacleShape mesh(RandomDraws& draws) {
  ObstacleShape s;
  if (draws.chance(0.6)) {
    const Eigen::Vector3d size_m(draws.logUniform(0.2, 2.5, 0.01), draws.logUniform(0.2, 2.5, 0.01),
                                 draws.logUniform(0.2, 2.5, 0.01));
    const std::string spec = "builtin:box?x=" + twoDecimals(size_m.x()) + "&y=" + twoDecimals(size_m.y()) +
                             "&z=" + twoDecimals(size_m.z()) + "&vertices=200";
    const double mass_kg = freeMass_kg(draws, 5, 5000);
    s = {mass_kg > 0 ? "free mesh box" : "mesh box",
         {{"type", "mesh"}, {"mesh", spec}, {"mass_kg", mass_kg}}};
    s.half_size_m = size_m.head<2>() / 2;
    s.yaw_to_path_deg = draws.uniform(-180, 180, 0.1);
    s.centre_height_m = size_m.z() / 2;
  } else {
    const double scale = draws.logUniform(4, 15, 0.01);
    const double mass_kg = freeMass_kg(draws, 5, 2000);
    s = {mass_kg > 0 ? "free drum" : "drum",
         {{"type", "mesh"},
          {"mesh", "builtin:can?vertices=600"},
          {"mesh_scale", scale},
          {"mass_kg", mass_kg}}};
    s.half_size_m = Eigen::Vector2d::Constant(kCanRadius_m * scale);
  }
  return s;
}

}  // namespace

ObstacleShape drawObstacleShape(RandomDraws& draws) {
  switch (draws.weighted({18, 18, 16, 16, 12, 12})) {
    case 0:
      return wall(draws);
    case 1:
      return post(draws);
    case 2:
      return box(draws);
    case 3:
      return vegetation(draws);
    case 4:
      return ramp(draws);
    default:
      return mesh(draws);
  }
}

Footprint obstacleFootprint(const ObstacleShape& shape, const Eigen::Vector2d& centre_m, double yaw_deg) {
  return {centre_m, yaw_deg * kDegree, shape.half_size_m};
}

nlohmann::json placeObstacle(const ObstacleShape& shape, Eigen::Vector2d& centre_m, double yaw_deg) {
  // A ramp's position is the middle of its low edge, half its length back from the footprint's centre.
  const Eigen::Vector2d to_centre_m = headingVector(yaw_deg * kDegree) * (shape.ramp_length_m / 2);
  Eigen::Vector2d position_m = centre_m - to_centre_m;
  position_m = {RandomDraws::rounded(position_m.x(), 1e-3), RandomDraws::rounded(position_m.y(), 1e-3)};
  centre_m = position_m + to_centre_m;
  nlohmann::json object = shape.keys;
  object["position_m"] = {position_m.x(), position_m.y(), shape.centre_height_m};
  object["yaw_deg"] = yaw_deg;
  return object;
}

}  // namespace sandbox
