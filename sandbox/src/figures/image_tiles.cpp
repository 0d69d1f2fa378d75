#include "image_tiles.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace sandbox::figures {

render::Image tileImages(const std::vector<render::Image>& panels, int columns, int gap_px) {
  if (panels.empty() || columns < 1) throw std::runtime_error("tileImages: no panels");
  const int w = panels.front().width, h = panels.front().height;
  for (const auto& p : panels)
    if (p.width != w || p.height != h) throw std::runtime_error("tileImages: panels differ in size");
  const int count = static_cast<int>(panels.size());
  const int cols = std::min(columns, count), rows = (count + cols - 1) / cols;
  render::Image out;
  out.width = cols * w + (cols - 1) * gap_px;
  out.height = rows * h + (rows - 1) * gap_px;
  out.rgba.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 4, 255);
  for (int i = 0; i < count; ++i) {
    const int x0 = (i % cols) * (w + gap_px), y0 = (i / cols) * (h + gap_px);
    for (int y = 0; y < h; ++y) {
      const auto* src = panels[static_cast<std::size_t>(i)].rgba.data() +
                        static_cast<std::size_t>(y) * static_cast<std::size_t>(w) * 4;
      auto* dst = out.rgba.data() + (static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(out.width) +
                                     static_cast<std::size_t>(x0)) *
                                        4;
      std::memcpy(dst, src, static_cast<std::size_t>(w) * 4);
    }
  }
  return out;
}

}  // namespace sandbox::figures
