#pragma once
// Shared by the render tests: pixel statistics of a picture.
#include "render/png_io.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>

namespace render_test {

/// Pixels that differ from `background` (by more than `tolerance` in any channel): their count, their
/// centroid and their extent, in pixel coordinates (x right, y down, pixel centres at +0.5).
struct Silhouette {
  std::size_t count = 0;
  Eigen::Vector2f centroid{0, 0};
  Eigen::Vector2f min{0, 0};
  Eigen::Vector2f max{0, 0};
};

/// An empty folder under the temporary directory, unique to `name` and this process (several engineers'
/// test runs share /tmp at the same time).
std::filesystem::path scratchDir(const std::string& name);

Silhouette silhouette(const sandbox::render::Image& image, const Eigen::Vector3i& background,
                      int tolerance = 6);

}  // namespace render_test
