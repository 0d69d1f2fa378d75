#pragma once
// Whether a straight path passes through the inside of an obstacle: the crash metrics' tunnelling test.
#include <vehicle/obstacle_shape.hpp>

#include <Eigen/Core>

namespace vehicle {

/// Whether the segment `from`-`to` passes through the inside of a box or an upright cylinder or capsule
/// (open: a segment that only touches the surface does not): exact for a box (its slabs); samples at most
/// a quarter of the radius apart, and 2 cm, along a cylinder or capsule (a chord shorter than that, within
/// 3 % of the radius of the rim, can be missed: a graze, not a tunnel). Any other shape: false.
bool segmentMeets(const ObstacleShape& shape, const Eigen::Vector3d& from, const Eigen::Vector3d& to);

}  // namespace vehicle
