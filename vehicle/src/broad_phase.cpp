#include "broad_phase.hpp"

namespace vehicle {

Box boxOf(const std::vector<Eigen::Vector3d>& points_m) {
  Box box{points_m.front(), points_m.front()};
  for (const Eigen::Vector3d& p : points_m) {
    box.min_m = box.min_m.cwiseMin(p);
    box.max_m = box.max_m.cwiseMax(p);
  }
  return box;
}

Box boxOf(const ObstacleShape& shape) {
  Box box;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d along = Eigen::Vector3d::Unit(axis);
    box.max_m[axis] = supportPoint(shape, along)[axis];
    box.min_m[axis] = supportPoint(shape, -along)[axis];
  }
  return box;
}

}  // namespace vehicle
