// The crush-profile measurement on its own (vehicle::crushProfile): stations across the struck end of a
// box, each the intrusion of the surface along the impact direction, NaN where the line misses it.
#include <vehicle/simulation.hpp>

#include <deform/control_mesh.hpp>

#include <catch2/catch.hpp>

#include <cmath>

namespace {

/// A 4 x 2 x 1 m box centred on the origin (x forward), as a closed convex control mesh.
deform::ControlMesh box() {
  std::vector<Eigen::Vector3d> corners;
  for (double x : {-2.0, 2.0})
    for (double y : {-1.0, 1.0})
      for (double z : {0.0, 1.0}) corners.emplace_back(x, y, z);
  return deform::convexHull(corners, "box", deform::FacetSplit::Diagonals);
}

}  // namespace

TEST_CASE("Crush profile: the stations of a pushed-in front, NaN where the line misses", "[crush][profile]") {
  const deform::ControlMesh mesh = box();
  const Eigen::Vector3d forward(1, 0, 0);
  std::vector<Eigen::Vector3d> now = mesh.points_m;

  SECTION("at rest every station reads zero") {
    const std::vector<double> rest = vehicle::crushProfile(mesh, now, forward, 0.5);
    REQUIRE(rest.size() == 6);
    for (double c : rest) CHECK(c == Approx(0).margin(1e-12));
  }
  SECTION("the front pushed back 0.3 m reads 0.3 m at every station") {
    for (auto& p : now)
      if (p.x() > 0) p.x() -= 0.3;
    const std::vector<double> crushed = vehicle::crushProfile(mesh, now, forward, 0.5);
    REQUIRE(crushed.size() == 6);
    for (double c : crushed) CHECK(c == Approx(0.3).epsilon(1e-9));
  }
  SECTION("the front's left edge pushed back: the stations on the left read more, in order along z x d") {
    // z x (1, 0, 0) = +y: the stations run from -y (C1) to +y (C6).
    for (auto& p : now)
      if (p.x() > 0 && p.y() > 0) p.x() -= 0.6;
    const std::vector<double> crushed = vehicle::crushProfile(mesh, now, forward, 0.5);
    REQUIRE(crushed.size() == 6);
    CHECK(crushed[0] < crushed[5]);
    CHECK(crushed[5] > 0.4);
    for (std::size_t j = 1; j < crushed.size(); ++j) CHECK(crushed[j] >= crushed[j - 1] - 1e-12);
  }
  SECTION("a height above the box: every station misses, and is NaN rather than left out") {
    const std::vector<double> above = vehicle::crushProfile(mesh, now, forward, 1.5);
    REQUIRE(above.size() == 6);
    for (double c : above) CHECK(std::isnan(c));
  }
}
