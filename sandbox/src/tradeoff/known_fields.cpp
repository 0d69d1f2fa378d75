#include "tradeoff/known_fields.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace sandbox {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d centreOf(const deform::Aabb& box) {
  return 0.5 * (box.min_m + box.max_m);
}

}  // namespace

KnownField bendField(const deform::Aabb& box) {
  const Eigen::Vector3d c = centreOf(box);
  const double length_m = box.size_m().x();
  const double kappa_per_m = 0.8 / (length_m * length_m);  // ends at s = +-L/2 rise kappa L^2 / 8 = 0.1 m
  return {"bend", "u = (-kappa s h, 0, kappa s^2 / 2), kappa = 0.8 / L^2 (ends rise 0.1 m)",
          [c, kappa_per_m](const Eigen::Vector3d& p) {
            const double s = p.x() - c.x(), h = p.z() - c.z();
            return Eigen::Vector3d(-kappa_per_m * s * h, 0, 0.5 * kappa_per_m * s * s);
          }};
}

KnownField twistField(const deform::Aabb& box) {
  const Eigen::Vector3d c = centreOf(box);
  const double length_m = box.size_m().x();
  const double twist_rad = 10.0 * kPi / 180.0;
  return {"twist", "sections turned about the long axis by theta = 10 deg s / L",
          [c, length_m, twist_rad](const Eigen::Vector3d& p) {
            const double theta = twist_rad * (p.x() - c.x()) / length_m;
            const double y = p.y() - c.y(), z = p.z() - c.z();
            const double ct = std::cos(theta), st = std::sin(theta);
            return Eigen::Vector3d(0, ct * y - st * z - y, st * y + ct * z - z);
          }};
}

KnownField crushField(const deform::Aabb& box) {
  const Eigen::Vector3d c = centreOf(box);
  const double front_m = box.max_m.x(), half_width_m = 0.5 * box.size_m().y();
  constexpr double kDepth_m = 1.5, kPush_m = 0.5, kBulge_m = 0.1;
  return {"crush",
          "d = x_max - x, w = (1 + cos(pi d / 1.5 m)) / 2 for d < 1.5 m (else 0), "
          "u = (-0.5 m w, 0.1 m w y' / (W/2), 0)",
          [c, front_m, half_width_m](const Eigen::Vector3d& p) {
            const double d = std::max(front_m - p.x(), 0.0);
            const double w = d < kDepth_m ? 0.5 * (1 + std::cos(kPi * d / kDepth_m)) : 0.0;
            return Eigen::Vector3d(-kPush_m * w, kBulge_m * w * (p.y() - c.y()) / half_width_m, 0);
          }};
}

KnownField affineField(const deform::Aabb& box) {
  const Eigen::Vector3d c = centreOf(box);
  Eigen::Matrix3d a;
  a << 0.02, 0.01, 0, -0.015, -0.01, 0.015, 0.005, -0.01, 0.01;
  const Eigen::Vector3d t(0.03, -0.02, 0.01);
  return {"affine", "u = A (p - centre) + t, |A| about 0.02, t = (0.03, -0.02, 0.01) m",
          [c, a, t](const Eigen::Vector3d& p) { return Eigen::Vector3d(a * (p - c) + t); }};
}

std::vector<KnownField> knownFields(const deform::Aabb& box) {
  return {bendField(box), twistField(box), crushField(box), affineField(box)};
}

}  // namespace sandbox
