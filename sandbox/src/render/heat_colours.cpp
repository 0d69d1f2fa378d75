#include "render/heat_colours.hpp"

#include <algorithm>
#include <cmath>

namespace deform {

Eigen::Vector3f heatColour(float t) {
  t = std::isfinite(t) ? std::clamp(t, 0.0f, 1.0f) : 1.0f;
  // Four linear segments between five stops, evenly spaced in t; red minus blue never falls.
  static const Eigen::Vector3f stops[5] = {{0.05f, 0.15f, 0.85f},
                                           {0.05f, 0.7f, 0.85f},
                                           {0.15f, 0.8f, 0.2f},
                                           {0.95f, 0.85f, 0.1f},
                                           {0.9f, 0.1f, 0.05f}};
  float x = t * 4.0f;
  int i = std::min(3, static_cast<int>(x));
  float f = x - static_cast<float>(i);
  return (1.0f - f) * stops[i] + f * stops[i + 1];
}

std::vector<Eigen::Vector3f> influenceColours(const Skin& skin, uint32_t control_index) {
  std::vector<Eigen::Vector3f> colours(skin.vertexCount());
  for (std::size_t j = 0; j < colours.size(); ++j) colours[j] = heatColour(skin.weight(j, control_index));
  return colours;
}

std::vector<Eigen::Vector3f> displacementColours(const std::vector<Eigen::Vector3f>& rest_m,
                                                 const std::vector<Eigen::Vector3f>& deformed_m,
                                                 float full_scale_m) {
  const std::size_t n = std::min(rest_m.size(), deformed_m.size());
  std::vector<float> moved(n);
  float largest = 0;
  for (std::size_t j = 0; j < n; ++j) {
    moved[j] = (deformed_m[j] - rest_m[j]).norm();
    largest = std::max(largest, moved[j]);
  }
  const float scale = full_scale_m > 0 ? full_scale_m : largest;
  std::vector<Eigen::Vector3f> colours(n);
  for (std::size_t j = 0; j < n; ++j) colours[j] = heatColour(scale > 0 ? moved[j] / scale : 0.0f);
  return colours;
}

}  // namespace deform
