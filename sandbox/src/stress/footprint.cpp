#include "stress/footprint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandbox {

Eigen::Vector2d headingVector(double yaw_rad) {
  return {std::cos(yaw_rad), std::sin(yaw_rad)};
}

double halfExtentAlong_m(const Footprint& f, const Eigen::Vector2d& direction) {
  const Eigen::Vector2d x = headingVector(f.yaw_rad);
  const Eigen::Vector2d y(-x.y(), x.x());
  return f.half_size_m.x() * std::abs(direction.dot(x)) + f.half_size_m.y() * std::abs(direction.dot(y));
}

double footprintGap_m(const Footprint& a, const Footprint& b) {
  const Eigen::Vector2d between = b.centre_m - a.centre_m;
  double gap_m = -std::numeric_limits<double>::infinity();
  for (const Footprint* f : {&a, &b}) {
    const Eigen::Vector2d x = headingVector(f->yaw_rad);
    for (const Eigen::Vector2d& axis : {x, Eigen::Vector2d(-x.y(), x.x())}) {
      const double apart_m =
          std::abs(between.dot(axis)) - halfExtentAlong_m(a, axis) - halfExtentAlong_m(b, axis);
      gap_m = std::max(gap_m, apart_m);
    }
  }
  return gap_m;
}

double travelToContact_m(const Footprint& moving, const Eigen::Vector2d& direction, const Footprint& still,
                         double farthest_m, double step_m) {
  Footprint moved = moving;
  for (double travel_m = 0; travel_m <= farthest_m; travel_m += step_m) {
    moved.centre_m = moving.centre_m + direction * travel_m;
    if (footprintGap_m(moved, still) <= 0) return travel_m;
  }
  return -1;
}

double gapToAll_m(const Footprint& candidate, const std::vector<Footprint>& placed) {
  double gap_m = std::numeric_limits<double>::max();
  for (const Footprint& f : placed) gap_m = std::min(gap_m, footprintGap_m(candidate, f));
  return gap_m;
}

}  // namespace sandbox
