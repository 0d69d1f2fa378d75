#pragma once
// Where a random scene's cars and obstacles stand on the ground, as rectangles seen from above: enough to
// keep every car clear of everything at the start (SceneRun refuses an overlap beyond 1 cm). Each shape's
// footprint holds the whole shape (a cylinder's is the square around its circle), so footprints apart
// means shapes apart.
#include <Eigen/Core>

#include <vector>

namespace sandbox {

struct Footprint {
  Eigen::Vector2d centre_m{0, 0};
  double yaw_rad = 0;                 ///< the rectangle's x axis from world X, about Z [rad]
  Eigen::Vector2d half_size_m{0, 0};  ///< half its extent along its own x and y [m]
};

/// How far apart two footprints are at least [m]: the largest gap between their projections on the four
/// axes of the two rectangles (separating axes); negative when they overlap.
double footprintGap_m(const Footprint& a, const Footprint& b);

/// The smallest footprintGap_m between `candidate` and any of `placed` (a large number for none).
double gapToAll_m(const Footprint& candidate, const std::vector<Footprint>& placed);

/// How far `moving` travels along the unit vector `direction` before it meets `still` [m], in steps of
/// `step_m`: 0 when they already touch, negative when they do not meet within `farthest_m`.
double travelToContact_m(const Footprint& moving, const Eigen::Vector2d& direction, const Footprint& still,
                         double farthest_m, double step_m = 0.02);

/// Half the extent of `f` along the direction `direction` (a unit vector) [m].
double halfExtentAlong_m(const Footprint& f, const Eigen::Vector2d& direction);

/// The unit vector at `yaw_rad` from world X.
Eigen::Vector2d headingVector(double yaw_rad);

}  // namespace sandbox
