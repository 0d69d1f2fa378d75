#include "render/sun_shadow.hpp"

#include <algorithm>
#include <vector>

namespace sandbox::render {

SunShadow fitSunShadow(const Eigen::AlignedBox3f& casters_m, float ground_height_m,
                       const Eigen::Vector3f& sun_direction, float penumbra_m, int map_size) {
  const Eigen::Vector3f l = sun_direction.normalized();
  // Light axes: look against the sun; any up that is not parallel to it.
  const Eigen::Vector3f forward = -l;
  const Eigen::Vector3f up_hint =
      std::abs(forward.z()) > 0.99f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitZ();
  const Eigen::Vector3f right = forward.cross(up_hint).normalized();
  const Eigen::Vector3f up = right.cross(forward);

  // The casters' corners and where the sun projects them onto the ground (the shadow's far end).
  std::vector<Eigen::Vector3f> points;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3f p = casters_m.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner));
    points.push_back(p);
    if (l.z() > 0.05f && p.z() > ground_height_m)
      points.push_back(p - l * ((p.z() - ground_height_m) / l.z()));
  }
  Eigen::Vector3f low = Eigen::Vector3f::Constant(1e30f), high = Eigen::Vector3f::Constant(-1e30f);
  for (const Eigen::Vector3f& p : points) {
    const Eigen::Vector3f q(p.dot(right), p.dot(up), p.dot(forward));
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  const Eigen::Vector3f size = (high - low).cwiseMax(Eigen::Vector3f::Constant(1e-4f));
  // Room for the PCF kernel at the borders, and depth slack so nothing is clipped.
  const float pad = 2.0f * penumbra_m;
  low.head<2>() -= Eigen::Vector2f::Constant(pad);
  high.head<2>() += Eigen::Vector2f::Constant(pad);
  low.z() -= 0.05f * size.z() + 1e-3f;
  high.z() += 0.05f * size.z() + 1e-3f;

  // Orthographic projection of the light-space box onto clip space [-1, 1]^3 (depth grows along forward).
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  const Eigen::Vector3f scale = (high - low).cwiseInverse() * 2.0f;
  const Eigen::Vector3f offset = -(high + low).cwiseProduct(scale) * 0.5f;
  m.block<1, 3>(0, 0) = right.transpose() * scale.x();
  m.block<1, 3>(1, 0) = up.transpose() * scale.y();
  m.block<1, 3>(2, 0) = forward.transpose() * scale.z();
  m.block<3, 1>(0, 3) = offset;

  SunShadow shadow;
  shadow.light_view_projection = m;
  const Eigen::Vector2f extent = (high - low).head<2>();
  shadow.pcf_radius_uv = Eigen::Vector2f(penumbra_m / extent.x(), penumbra_m / extent.y());
  const float texel_m = std::max(extent.x(), extent.y()) / static_cast<float>(std::max(map_size, 1));
  shadow.depth_bias = 1.5f * texel_m / (high.z() - low.z());
  shadow.slope_bias = (penumbra_m + texel_m) / (high.z() - low.z());
  return shadow;
}

}  // namespace sandbox::render
