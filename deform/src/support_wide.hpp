#pragma once
// The support of a point set, four points at a time where AVX2 runs (ConvexPoints::support).
#include <Eigen/Core>
#include <cstddef>

namespace deform {

/// The index of the first of points[0 .. n) with the largest p . direction (n >= 1): the one-at-a-time
/// scan's answer, to the bit and on ties. `wide`: four at a time where the machine can; a direction or a
/// point whose products are not finite is scanned one at a time.
std::size_t farthestAlong(const Eigen::Vector3d* points, std::size_t n, const Eigen::Vector3d& direction,
                          bool wide);

}  // namespace deform
