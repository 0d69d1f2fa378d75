// front_profile: the front-most x per slice across the width, and its spread over the middle of it.
#include <figures/front_profile.hpp>

#include <catch2/catch.hpp>

#include <cmath>

TEST_CASE("front profile: a flat front has no spread, a pointed nose spreads by its slope",
          "[figures][front_profile]") {
  deform::Aabb box;
  box.min_m = {-2, -1, 0};
  box.max_m = {2, 1, 1};
  // Vertices every 1 cm across the width at the front (x = 2), and a point far behind in every slice.
  std::vector<Eigen::Vector3f> flat, nose;
  for (int i = 0; i <= 200; ++i) {
    const float y = -1.0f + 0.01f * static_cast<float>(i);
    flat.push_back({2.0f, y, 0.5f});
    flat.push_back({-2.0f, y, 0.5f});
    nose.push_back({2.0f - 0.5f * std::abs(y), y, 0.5f});  // 0.5 m back per metre out from the middle
  }
  const auto flat_profile = sandbox::figures::frontProfile(flat, box);
  REQUIRE(flat_profile.y_m.size() == 20);  // 2 m in 0.1 m slices
  CHECK(flat_profile.variation_m == Approx(0).margin(1e-6));
  for (double x : flat_profile.front_x_m) CHECK(x == Approx(2.0));
  // Middle 80 %: slice centres within 0.8 m of the axis, the outermost at |y| = 0.75 m, whose front-most
  // vertex sits at |y| = 0.70-0.71 m (0.35-0.355 m back); the middle slice reaches x = 2 (y = 0).
  const auto nose_profile = sandbox::figures::frontProfile(nose, box);
  CHECK(nose_profile.variation_m == Approx(0.35).margin(0.006));
}
