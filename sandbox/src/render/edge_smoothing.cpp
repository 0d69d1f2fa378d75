#include "render/edge_smoothing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace sandbox::render {
namespace {

// The picture as luma and colour, sampled with clamping at the borders and bilinear filtering.
class Picture {
 public:
  Picture(int width, int height, const std::vector<uint8_t>& rgba)
      : width_(width), height_(height), rgba_(rgba) {
    luma_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
    for (std::size_t i = 0; i < luma_.size(); ++i) {
      const uint8_t* p = rgba_.data() + 4 * i;
      // Rec. 601 weights on the display values: the contrast a viewer sees.
      luma_[i] = (0.299f * static_cast<float>(p[0]) + 0.587f * static_cast<float>(p[1]) +
                  0.114f * static_cast<float>(p[2])) *
                 (1.0f / 255.0f);
    }
  }

  float luma(int x, int y) const { return luma_[index(x, y)]; }
  /// Row y's luma, the nearest row for one outside the picture.
  const float* lumaRow(int y) const { return luma_.data() + index(0, y); }

  // Bilinear luma at pixel coordinates (pixel centres at integers).
  float luma(float x, float y) const {
    const float fx = std::floor(x), fy = std::floor(y);
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const float tx = x - fx, ty = y - fy;
    const float top = luma(x0, y0) + (luma(x0 + 1, y0) - luma(x0, y0)) * tx;
    const float bottom = luma(x0, y0 + 1) + (luma(x0 + 1, y0 + 1) - luma(x0, y0 + 1)) * tx;
    return top + (bottom - top) * ty;
  }

  // Bilinear colour at pixel coordinates, rounded to 8 bits.
  std::array<uint8_t, 3> colour(float x, float y) const {
    const float fx = std::floor(x), fy = std::floor(y);
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const float tx = x - fx, ty = y - fy;
    const uint8_t* a = rgba_.data() + 4 * index(x0, y0);
    const uint8_t* b = rgba_.data() + 4 * index(x0 + 1, y0);
    const uint8_t* c = rgba_.data() + 4 * index(x0, y0 + 1);
    const uint8_t* d = rgba_.data() + 4 * index(x0 + 1, y0 + 1);
    std::array<uint8_t, 3> out{};
    for (int k = 0; k < 3; ++k) {
      const auto value = [k](const uint8_t* pixel) { return static_cast<float>(pixel[k]); };
      const float top = value(a) + (value(b) - value(a)) * tx;
      const float bottom = value(c) + (value(d) - value(c)) * tx;
      out[static_cast<std::size_t>(k)] = static_cast<uint8_t>(std::lround(top + (bottom - top) * ty));
    }
    return out;
  }

 private:
  std::size_t index(int x, int y) const {
    x = std::clamp(x, 0, width_ - 1);
    y = std::clamp(y, 0, height_ - 1);
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }

  int width_, height_;
  const std::vector<uint8_t>& rgba_;
  std::vector<float> luma_;
};

// FXAA 3.11's quality preset 12: how far each step of the search along an edge goes [px].
constexpr std::array<float, 8> kSearchSteps = {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f};

}  // namespace

void smoothEdges(Image& image, const EdgeSmoothing& settings) {
  if (image.width < 3 || image.height < 3) return;
  // Read from a copy: the pass writes into image.rgba.
  const std::vector<uint8_t> source = image.rgba;
  const Picture picture(image.width, image.height, source);
  for (int y = 0; y < image.height; ++y) {
    // Most pixels stop at the contrast test: it reads three rows directly.
    const float *up = picture.lumaRow(y - 1), *row = picture.lumaRow(y), *down = picture.lumaRow(y + 1);
    for (int x = 0; x < image.width; ++x) {
      const int left = x > 0 ? x - 1 : 0, right = x + 1 < image.width ? x + 1 : x;
      const float m = row[x];
      float n = up[x], s = down[x];
      float w = row[left], e = row[right];
      const float highest = std::max({m, n, s, w, e}), lowest = std::min({m, n, s, w, e});
      const float range = highest - lowest;
      if (range < std::max(settings.edge_threshold_min, highest * settings.edge_threshold)) continue;

      const float nw = picture.luma(x - 1, y - 1), ne = picture.luma(x + 1, y - 1);
      const float sw = picture.luma(x - 1, y + 1), se = picture.luma(x + 1, y + 1);
      // Sub-pixel blend: how much the pixel stands out from the average around it.
      const float around = (2.0f * (n + s + w + e) + nw + ne + sw + se) / 12.0f;
      const float stand_out = std::clamp(std::abs(around - m) / range, 0.0f, 1.0f);
      const float smooth = (-2.0f * stand_out + 3.0f) * stand_out * stand_out;
      const float subpixel_blend = smooth * smooth * settings.subpixel;

      // A horizontal edge (brightness changes along y) or a vertical one.
      const float horizontal =
          std::abs(-2.0f * w + nw + sw) + 2.0f * std::abs(-2.0f * m + n + s) + std::abs(-2.0f * e + ne + se);
      const float vertical =
          std::abs(-2.0f * n + nw + ne) + 2.0f * std::abs(-2.0f * m + w + e) + std::abs(-2.0f * s + sw + se);
      const bool horizontal_edge = horizontal >= vertical;
      if (!horizontal_edge) {
        n = w;
        s = e;
      }
      // Which side of the pixel the edge runs on: the neighbour with the steeper gradient.
      const float gradient_n = n - m, gradient_s = s - m;
      const bool pair_n = std::abs(gradient_n) >= std::abs(gradient_s);
      const float gradient = std::max(std::abs(gradient_n), std::abs(gradient_s));
      const float side = pair_n ? -1.0f : 1.0f;
      const float pair_luma = (pair_n ? n : s) + m;

      // Walk both ways along the edge, half a pixel towards that side, until its contrast ends.
      const float bx = horizontal_edge ? static_cast<float>(x) : static_cast<float>(x) + 0.5f * side;
      const float by = horizontal_edge ? static_cast<float>(y) + 0.5f * side : static_cast<float>(y);
      const float dx = horizontal_edge ? 1.0f : 0.0f, dy = horizontal_edge ? 0.0f : 1.0f;
      const float gradient_scaled = gradient * 0.25f;
      const bool centre_below = m - 0.5f * pair_luma < 0.0f;
      float offset_n = 0.0f, offset_p = 0.0f, end_n = 0.0f, end_p = 0.0f;
      bool done_n = false, done_p = false;
      for (float step : kSearchSteps) {
        if (!done_n) {
          offset_n += step;
          end_n = picture.luma(bx - dx * offset_n, by - dy * offset_n) - 0.5f * pair_luma;
          done_n = std::abs(end_n) >= gradient_scaled;
        }
        if (!done_p) {
          offset_p += step;
          end_p = picture.luma(bx + dx * offset_p, by + dy * offset_p) - 0.5f * pair_luma;
          done_p = std::abs(end_p) >= gradient_scaled;
        }
        if (done_n && done_p) break;
      }
      // FXAA's first probe sits a step out; its distances count from the pixel.
      const bool nearer_n = offset_n < offset_p;
      const float distance = std::min(offset_n, offset_p);
      const bool good_span = nearer_n ? (end_n < 0.0f) != centre_below : (end_p < 0.0f) != centre_below;
      const float edge_blend = good_span ? 0.5f - distance / (offset_n + offset_p) : 0.0f;
      const float blend = std::max(edge_blend, subpixel_blend);
      if (blend <= 0.0f) continue;
      const float sx = horizontal_edge ? static_cast<float>(x) : static_cast<float>(x) + blend * side;
      const float sy = horizontal_edge ? static_cast<float>(y) + blend * side : static_cast<float>(y);
      const std::array<uint8_t, 3> c = picture.colour(sx, sy);
      uint8_t* out =
          image.rgba.data() + 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                   static_cast<std::size_t>(x));
      out[0] = c[0];
      out[1] = c[1];
      out[2] = c[2];
    }
  }
}

}  // namespace sandbox::render
