#pragma once
// Anti-aliasing after the fact (FXAA 3.11's algorithm, on the CPU): a pixel whose neighbours' brightness
// jumps is blended along the edge it lies on. llvmpipe's 4x MSAA adds two thirds to the cost of a 720p
// frame; this pass gives edges that look as smooth for 15-20 ms of one core, off the render thread.
#include "render/png_io.hpp"

namespace sandbox::render {

/// FXAA's defaults but a lighter sub-pixel blend: the ground's grid lines are anti-aliased by their shader
/// already, and blurring them took the frames further from 4x MSAA's.
struct EdgeSmoothing {
  float edge_threshold = 0.166f;       ///< smallest local contrast smoothed, relative to the brightest [-]
  float edge_threshold_min = 0.0312f;  ///< smallest local contrast smoothed in dark areas [0..1 luma]
  float subpixel = 0.5f;  ///< how much single-pixel detail (thin lines, specks) is softened [0..1]
};

/// Smooths the edges of `image` (RGBA8, alpha kept). Deterministic; pixels away from edges unchanged.
void smoothEdges(Image& image, const EdgeSmoothing& settings = {});

}  // namespace sandbox::render
