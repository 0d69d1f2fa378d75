#pragma once
// Putting several rendered panels into one figure.
#include <string>
#include <vector>

#include "render/png_io.hpp"

namespace sandbox::figures {

/// Panels laid out left to right, top to bottom, `columns` per row, separated by `gap_px` white pixels.
/// Every panel must have the same size.
render::Image tileImages(const std::vector<render::Image>& panels, int columns, int gap_px = 8);

}  // namespace sandbox::figures
