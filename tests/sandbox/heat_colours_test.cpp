#include "render/heat_colours.hpp"

#include <catch2/catch.hpp>

#include "deform/point_sets.hpp"

TEST_CASE("heat colours run from blue (none) to red (most)", "[colours]") {
  const Eigen::Vector3f none = deform::heatColour(0.0f), most = deform::heatColour(1.0f);
  CHECK(none.z() > 0.8f);
  CHECK(none.x() < 0.1f);
  CHECK(most.x() > 0.8f);
  CHECK(most.z() < 0.1f);
  CHECK(deform::heatColour(-3.0f) == none);
  CHECK(deform::heatColour(7.0f) == most);
  // Red rises and blue falls, never the other way, along the ramp.
  float previous_red_minus_blue = -2.0f;
  for (int i = 0; i <= 100; ++i) {
    Eigen::Vector3f c = deform::heatColour(static_cast<float>(i) / 100.0f);
    REQUIRE(c.minCoeff() >= 0.0f);
    REQUIRE(c.maxCoeff() <= 1.0f);
    REQUIRE(c.x() - c.z() >= previous_red_minus_blue - 1e-6f);
    previous_red_minus_blue = c.x() - c.z();
  }
}

TEST_CASE("influence and displacement colours mark the right vertices", "[colours]") {
  std::vector<Eigen::Vector3d> control = test_points::sphere(40);
  std::vector<Eigen::Vector3f> vertices;
  for (const auto& c : control) vertices.push_back(c.cast<float>());
  std::vector<Eigen::Vector3d> exact;
  for (const auto& v : vertices) exact.push_back(v.cast<double>());
  auto skin = deform::Skin::build(vertices, exact, {4.0, 8, 1});
  auto colours = deform::influenceColours(skin, 5);
  CHECK(colours[5] == deform::heatColour(1.0f));   // on the control point: all its weight
  CHECK(colours[30] == deform::heatColour(0.0f));  // far side: none

  std::vector<Eigen::Vector3f> moved = vertices;
  moved[2] += Eigen::Vector3f(0, 0, 0.1f);
  moved[3] += Eigen::Vector3f(0, 0.05f, 0);
  auto heat = deform::displacementColours(vertices, moved);
  CHECK(heat[2] == deform::heatColour(1.0f));
  CHECK((heat[3] - deform::heatColour(0.5f)).norm() < 1e-5f);
  CHECK(heat[0] == deform::heatColour(0.0f));
  auto fixed_scale = deform::displacementColours(vertices, moved, 0.2f);
  CHECK((fixed_scale[2] - deform::heatColour(0.5f)).norm() < 1e-5f);
}
