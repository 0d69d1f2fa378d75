#pragma once
// A rigid placement in the world (DESIGN.md section 2: metres, right-handed, Z up).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vehicle {

/// Where a frame is: the world position of its origin and the rotation from the frame to the world.
struct Pose {
  Eigen::Vector3d position_m{0, 0, 0};                              ///< origin in the world [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< frame -> world rotation (unit)

  /// Point given in this frame, expressed in the world [m].
  Eigen::Vector3d toWorld(const Eigen::Vector3d& local_m) const { return position_m + orientation * local_m; }
  /// World point expressed in this frame [m].
  Eigen::Vector3d toLocal(const Eigen::Vector3d& world_m) const {
    return orientation.conjugate() * (world_m - position_m);
  }
  Eigen::Isometry3d isometry() const {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = orientation.toRotationMatrix();
    t.translation() = position_m;
    return t;
  }
  /// The pose of the world in this frame (the inverse transform).
  Pose inverse() const {
    const Eigen::Quaterniond q = orientation.conjugate();
    return Pose{-(q * position_m), q};
  }
  /// A pose at `position_m` turned by `heading_rad` about the world Z axis (0: X forward).
  static Pose yawed(const Eigen::Vector3d& position_m, double heading_rad) {
    return Pose{position_m, Eigen::Quaterniond(Eigen::AngleAxisd(heading_rad, Eigen::Vector3d::UnitZ()))};
  }
};

}  // namespace vehicle
