#pragma once
// The car the crush tests crash: the built-in sedan, coarse (only its control mesh matters for the
// physics), built once per test binary.
#include <vehicle/simulation.hpp>

#include <deform/builtin_meshes.hpp>

#include <algorithm>

namespace crash_test {

inline constexpr double kKmh = 1 / 3.6;

inline const deform::VehicleModel& sedan() {
  static const deform::VehicleModel model = deform::makeBuiltin("builtin:sedan?vertices=2000");
  return model;
}

/// The foremost x of a car's control points at rest, in its own frame [m].
inline double frontOf(const vehicle::Simulation& sim, vehicle::CarId id) {
  double front = -1e300;
  for (const auto& p : sim.controlRestPoints(id)) front = std::max(front, p.x());
  return front;
}

}  // namespace crash_test
