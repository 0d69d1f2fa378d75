#pragma once
// The heat-map colour ramp of the paper's figures: blue where nothing moved, red where most moved.
#include <Eigen/Core>

namespace sandbox::render {

/// sRGB colour in [0, 1] for t in [0, 1] (clamped; NaN counts as 1): blue (none) -> cyan -> green ->
/// yellow -> red (most). Piecewise linear between five evenly spaced stops, so the hue falls
/// monotonically from 240 to 0 degrees as t grows and every stop is a fully saturated primary or
/// secondary colour that survives video compression.
Eigen::Vector3f heatColour(float t);

}  // namespace sandbox::render
