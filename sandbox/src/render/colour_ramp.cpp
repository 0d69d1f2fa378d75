#include "render/colour_ramp.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace sandbox::render {

Eigen::Vector3f heatColour(float t) {
  t = std::isnan(t) ? 1.0f : std::clamp(t, 0.0f, 1.0f);
  // Slightly darkened primaries: full-intensity cyan and yellow look washed out next to the lit body.
  static const std::array<Eigen::Vector3f, 5> stops = {
      Eigen::Vector3f{0.05f, 0.10f, 0.95f},  // blue: untouched
      Eigen::Vector3f{0.00f, 0.80f, 0.90f},  // cyan
      Eigen::Vector3f{0.10f, 0.85f, 0.15f},  // green
      Eigen::Vector3f{0.95f, 0.90f, 0.05f},  // yellow
      Eigen::Vector3f{0.95f, 0.08f, 0.05f},  // red: most moved
  };
  const float x = t * 4.0f;
  const int segment = std::min(3, static_cast<int>(x));
  const float f = x - static_cast<float>(segment);
  return (1.0f - f) * stops[static_cast<std::size_t>(segment)] +
         f * stops[static_cast<std::size_t>(segment) + 1];
}

}  // namespace sandbox::render
