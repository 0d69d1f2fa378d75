#pragma once
// Small helpers the stress suite and the random campaign share.
#include <Eigen/Core>

#include <cstdio>
#include <numbers>
#include <string>

namespace sandbox::stress_support {

constexpr double kDegree = std::numbers::pi / 180.0;  ///< one degree [rad]
constexpr double kHuge = 1e10;                        ///< MuJoCo-style divergence bound

/// Finite, and every coordinate under kHuge.
inline bool bounded(const Eigen::Vector3d& v) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() < kHuge;
}

/// `pattern` (printf, up to four doubles) filled in, up to 255 characters.
inline std::string format(const char* pattern, double a, double b = 0, double c = 0, double d = 0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c, d);
  return text;
}

}  // namespace sandbox::stress_support
