#pragma once
// The shell orientation constraint's two passes (shellRotation, turnShell in constraints.hpp) four points
// at a time where AVX2 runs: each lane does their operations in their order and the sums are added lane
// by lane in point order, so the results are the same bits (the test `the wide sweep...`).
#include <Eigen/Core>
#include <cstddef>

namespace deform {

/// shellRotation over points [0, n); `wide`: four at a time where the machine can.
Eigen::Vector3d shellRotationWide(const Eigen::Vector3d* x, const Eigen::Vector3d* x0, const double* mass_kg,
                                  std::size_t n, const Eigen::Vector3d& core_m,
                                  const Eigen::Vector3d& shift_m, bool wide);

/// turnShell over points [0, n); `wide`: four at a time where the machine can.
Eigen::Vector3d turnShellWide(Eigen::Vector3d* x, const Eigen::Vector3d* x0, const double* mass_kg,
                              std::size_t n, const Eigen::Vector3d& core_m, const Eigen::Vector3d& shift_m,
                              const Eigen::Vector3d& mu, Eigen::Vector3d& push, bool wide);

}  // namespace deform
