// The crash metrics' tunnelling test (segment_meets.hpp).
#include "segment_meets.hpp"

#include <algorithm>
#include <cmath>

namespace vehicle {

bool segmentMeets(const ObstacleShape& shape, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  if (shape.type == ShapeType::Box) {
    // The part of the segment inside each slab |local_k| < half_k, intersected (open: touching is not in).
    const Eigen::Vector3d a = shape.axes.transpose() * (from - shape.centre_m);
    const Eigen::Vector3d d = shape.axes.transpose() * (to - from);
    double enter = 0, leave = 1;
    for (int k = 0; k < 3; ++k) {
      const double half = shape.half_extents_m[k];
      if (d[k] == 0) {
        if (!(std::abs(a[k]) < half)) return false;
        continue;
      }
      const double t0 = (-half - a[k]) / d[k], t1 = (half - a[k]) / d[k];
      enter = std::max(enter, std::min(t0, t1));
      leave = std::min(leave, std::max(t0, t1));
    }
    return enter < leave;
  }
  if (shape.type != ShapeType::Cylinder && shape.type != ShapeType::Capsule) return false;
  const double length = (to - from).norm();
  const double spacing_m = std::min(0.02, 0.25 * shape.radius_m);
  const int samples =
      spacing_m > 0 ? std::clamp(static_cast<int>(std::ceil(length / spacing_m)), 1, 100000) : 1;
  const Eigen::Vector3d ab = shape.b_m - shape.a_m;
  for (int k = 0; k <= samples; ++k) {
    const Eigen::Vector3d p = from + (to - from) * (static_cast<double>(k) / samples);
    const double t = ab.squaredNorm() > 0 ? (p - shape.a_m).dot(ab) / ab.squaredNorm() : 0.0;
    if (t < 0 || t > 1) continue;
    if ((p - shape.a_m - t * ab).norm() < shape.radius_m) return true;
  }
  return false;
}

}  // namespace vehicle
