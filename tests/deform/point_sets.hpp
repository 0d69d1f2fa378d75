#pragma once
// Deterministic point sets for geometry tests (no dependency on the mesh generators).
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

namespace test_points {

/// `count` points spread over a sphere (Fibonacci lattice), optionally stretched per axis.
inline std::vector<Eigen::Vector3d> sphere(std::size_t count, const Eigen::Vector3d& radii_m = {1, 1, 1}) {
  std::vector<Eigen::Vector3d> points;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < count; ++i) {
    double z = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(count);
    double r = std::sqrt(1.0 - z * z), phi = golden * static_cast<double>(i);
    points.emplace_back(radii_m.x() * r * std::cos(phi), radii_m.y() * r * std::sin(phi), radii_m.z() * z);
  }
  return points;
}

/// The same set with its mirror image in Y added exactly (y -> -y), for symmetry tests.
inline std::vector<Eigen::Vector3d> mirroredInY(const std::vector<Eigen::Vector3d>& half) {
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : half) {
    if (p.y() <= 0) continue;
    points.push_back(p);
    points.emplace_back(p.x(), -p.y(), p.z());
  }
  return points;
}

/// Pseudo-random points in the unit cube [-0.5, 0.5]^3 (fixed LCG: same on every machine).
inline std::vector<Eigen::Vector3d> cloud(std::size_t count, uint64_t seed = 1) {
  std::vector<Eigen::Vector3d> points;
  auto next = [&seed] {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5;
  };
  for (std::size_t i = 0; i < count; ++i) {
    double x = next(), y = next(), z = next();
    points.emplace_back(x, y, z);
  }
  return points;
}

}  // namespace test_points
