// Edges smoothed after the readback: a staircase gets the in-between shades multisampling would give,
// flat areas keep their pixels, and a frame of the fast path stays within a fraction of a level of 4x
// MSAA's.
#include <catch2/catch.hpp>

#include <deform/builtin_meshes.hpp>

#include <algorithm>
#include <cstdlib>
#include <set>

#include "render/edge_smoothing.hpp"
#include "render/renderer.hpp"

using namespace sandbox::render;

namespace {

Image filled(int width, int height, uint8_t grey) {
  Image image{width, height, std::vector<uint8_t>(static_cast<std::size_t>(width * height) * 4, grey)};
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
  return image;
}

uint8_t& red(Image& image, int x, int y) {
  return image.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                     static_cast<std::size_t>(x)) *
                    4];
}

// Mean absolute difference over the colour channels [levels of 255].
double meanDifference(const Image& a, const Image& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4)
    for (std::size_t c = 0; c < 3; ++c) sum += std::abs(int{a.rgba[i + c]} - int{b.rgba[i + c]});
  return sum / static_cast<double>(a.rgba.size() / 4 * 3);
}

int largestChannelDifference(const Image& a, const Image& b, std::size_t i) {
  int largest = 0;
  for (std::size_t c = 0; c < 3; ++c)
    largest = std::max(largest, std::abs(int{a.rgba[i + c]} - int{b.rgba[i + c]}));
  return largest;
}

}  // namespace

TEST_CASE("edge smoothing blends a jagged edge and leaves flat areas alone", "[render]") {
  Image flat = filled(32, 24, 90);
  const Image flat_before = flat;
  smoothEdges(flat);
  CHECK(flat.rgba == flat_before.rgba);

  // Black below a shallow staircase (one step down every four pixels), white above.
  Image stairs = filled(64, 32, 255);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      if (y >= 8 + x / 4)
        for (int c = 0; c < 3; ++c)
          stairs.rgba[(static_cast<std::size_t>(y) * 64 + static_cast<std::size_t>(x)) * 4 +
                      static_cast<std::size_t>(c)] = 0;
  Image smoothed = stairs;
  smoothEdges(smoothed);
  std::set<int> shades;
  for (int x = 4; x < 56; ++x)
    for (int y = 6; y < 24; ++y) shades.insert(red(smoothed, x, y));
  CHECK(shades.size() > 4);  // in-between greys along the edge, not just black and white
  // Far from the edge nothing moves.
  CHECK(red(smoothed, 60, 2) == 255);
  CHECK(red(smoothed, 2, 30) == 0);
  // Deterministic.
  Image again = stairs;
  smoothEdges(again);
  CHECK(again.rgba == smoothed.rgba);
}

TEST_CASE("a frame with smoothed edges matches the 4x MSAA frame within a fraction of a level", "[render]") {
  const deform::Mesh box_mesh = deform::makeBox({1.0, 1.0, 1.0}, 200);
  const deform::Aabb box = deform::boundingBox(box_mesh);
  const auto frame = [&](const RenderSettings& settings) {
    Renderer renderer(settings);
    renderer.addMesh(meshData(box_mesh, {0.2f, 0.4f, 0.9f}));
    return renderer.renderImage(presetCamera("quarter", box, renderer.aspect()), environmentAround(box));
  };
  RenderSettings msaa{320, 180, 4};
  RenderSettings smoothed = msaa;
  smoothed.smooth_edges = true;
  const Image reference = frame(msaa), fast = frame(smoothed);
  RenderSettings plain = msaa;
  plain.samples = 0;
  const Image jagged = frame(plain);
  // On the edges multisampling smoothed (where the frame without anti-aliasing differs from it), the
  // smoothed frame comes closer to it; over the whole frame it stays within a fraction of a level.
  double jagged_error = 0, fast_error = 0;
  std::size_t edge_pixels = 0;
  for (std::size_t i = 0; i < reference.rgba.size(); i += 4) {
    if (largestChannelDifference(jagged, reference, i) <= 8) continue;
    jagged_error += largestChannelDifference(jagged, reference, i);
    fast_error += largestChannelDifference(fast, reference, i);
    ++edge_pixels;
  }
  REQUIRE(edge_pixels > 50);
  CHECK(fast_error < 0.8 * jagged_error);
  const double fast_difference = meanDifference(fast, reference);
  CHECK(fast_difference < 1.0);
}
