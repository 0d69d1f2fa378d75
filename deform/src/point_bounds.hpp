#pragma once
// The axis-aligned bounds of a non-empty set of points.
#include <Eigen/Core>
#include <vector>

namespace deform::detail {

/// The smallest coordinate of `points` on each axis (non-empty) [m].
inline Eigen::Vector3d lowest(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d m = points.front();
  for (const auto& p : points) m = m.cwiseMin(p);
  return m;
}

/// The largest coordinate of `points` on each axis (non-empty) [m].
inline Eigen::Vector3d highest(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d m = points.front();
  for (const auto& p : points) m = m.cwiseMax(p);
  return m;
}

}  // namespace deform::detail
