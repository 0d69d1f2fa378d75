#pragma once
// The visual constraint's list of points near their caps (DeformableBody::capDeviation), four points at a
// time where AVX2 runs: each lane does the one-at-a-time test's operations in their order, so the list is
// the same (the test `the visual constraint's near list...`).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace deform {

/// Appends to `near`, in order, each point i of [begin, end) whose deviation
/// d = x_i - (rest_i + core - core_rest) may reach past max_deviation_i - reduced_by: those with
/// max_deviation_i - reduced_by <= 0 or not |d|^2 <= (max_deviation_i - reduced_by)^2 (a deviation that is
/// not a number included). `wide`: four at a time where the machine can.
void listNearCaps(const Eigen::Vector3d* x, const Eigen::Vector3d* rest_m, const double* max_deviation_m,
                  const Eigen::Vector3d& core_m, const Eigen::Vector3d& core_rest_m, double reduced_by_m,
                  std::size_t begin, std::size_t end, bool wide, std::vector<uint32_t>& near);

}  // namespace deform
