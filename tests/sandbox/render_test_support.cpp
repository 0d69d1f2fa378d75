#include "render_test_support.hpp"

#include <unistd.h>
#include <algorithm>
#include <cstdlib>

namespace render_test {

std::filesystem::path scratchDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sandbox_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

Silhouette silhouette(const sandbox::render::Image& image, const Eigen::Vector3i& background, int tolerance) {
  Silhouette s;
  Eigen::Vector2d sum(0, 0);
  s.min = Eigen::Vector2f::Constant(1e9f);
  s.max = Eigen::Vector2f::Constant(-1e9f);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                      static_cast<std::size_t>(x)) *
                                     4];
      bool differs = false;
      for (int c = 0; c < 3; ++c) differs = differs || std::abs(int{p[c]} - background[c]) > tolerance;
      if (!differs) continue;
      const Eigen::Vector2f centre(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      ++s.count;
      sum += centre.cast<double>();
      s.min = s.min.cwiseMin(centre);
      s.max = s.max.cwiseMax(centre);
    }
  }
  if (s.count > 0) s.centroid = (sum / static_cast<double>(s.count)).cast<float>();
  return s;
}

}  // namespace render_test
