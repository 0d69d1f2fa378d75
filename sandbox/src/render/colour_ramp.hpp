#pragma once
// The heat-map colour ramp of the paper's figures: blue where nothing moved, red where most moved.
#include <Eigen/Core>

namespace sandbox::render {

/// sRGB colour in [0, 1] for t in [0, 1] (clamped; NaN counts as 1): blue (none) -> cyan -> green ->
/// yellow -> red (most), piecewise linear between five evenly spaced stops, so the hue falls
/// monotonically from blue to red as t grows. The stops themselves live in deform::heatColour
/// (deform/heat_colours.hpp), which colours displacements and influences for `sandbox run`: one ramp,
/// so a picture from `mesh render --heatmap-point` and a crash video use the same colours.
Eigen::Vector3f heatColour(float t);

}  // namespace sandbox::render
