#include "render/colour_ramp.hpp"

#include "render/heat_colours.hpp"

#include <cmath>

namespace sandbox::render {

Eigen::Vector3f heatColour(float t) {
  // NaN is shown as the worst, never as untouched; infinities clamp to their end of the ramp.
  if (std::isnan(t)) return deform::heatColour(1.0f);
  return deform::heatColour(std::isinf(t) ? (t > 0 ? 1.0f : 0.0f) : t);
}

}  // namespace sandbox::render
