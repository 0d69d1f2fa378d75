#pragma once
// The car the crush tests crash: the built-in sedan, coarse (only its control mesh matters for the
// physics), built once per test binary.
#include <deform/builtin_meshes.hpp>

namespace crash_test {

inline constexpr double kKmh = 1 / 3.6;

inline const deform::VehicleModel& sedan() {
  static const deform::VehicleModel model = deform::makeBuiltin("builtin:sedan?vertices=2000");
  return model;
}

}  // namespace crash_test
