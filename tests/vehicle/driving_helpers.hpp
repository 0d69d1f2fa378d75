#pragma once
// Shared set-up and measurements for the driving tests.
#include <vehicle/world.hpp>

#include <deform/builtin_meshes.hpp>

#include <Eigen/Geometry>
#include <cmath>

namespace vehicle_test {

/// The built-in sedan (its body mesh at a modest resolution: the chassis only needs its hull).
inline const deform::VehicleModel& drivingSedan() {
  static const deform::VehicleModel model = deform::makeSedan(4000);
  return model;
}

/// Pitch (nose up +) and roll (right side down +) of a pose, from its rotated X and Y axes [rad].
inline double pitch_rad(const vehicle::Pose& pose) {
  const Eigen::Vector3d x = pose.orientation * Eigen::Vector3d::UnitX();
  return std::asin(std::clamp(x.z(), -1.0, 1.0));
}
inline double roll_rad(const vehicle::Pose& pose) {
  const Eigen::Vector3d y = pose.orientation * Eigen::Vector3d::UnitY();
  return std::asin(std::clamp(y.z(), -1.0, 1.0));
}
inline double heading_rad(const vehicle::Pose& pose) {
  const Eigen::Vector3d x = pose.orientation * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

}  // namespace vehicle_test
