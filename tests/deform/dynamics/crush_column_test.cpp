// Crush columns held at a rest place (BodyDescription::anchored_columns): a column resists a motion of its
// point by the volume its patch of skin sweeps, |a . d| per metre of travel, whatever the slope of the
// patch. The return map and the yield are pure functions (constraints.hpp), checked here against
// hand-worked values, and on a 60-point hull built by createBodySettings (its columns' areas and yields).
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/constraints.hpp>
#include <deform/deformable_body.hpp>

#include <cmath>

using namespace deform;
using namespace dynamics_test;

TEST_CASE("Crush column: the yield displacement is the patch's area seen along the push", "[dynamics]") {
  const Eigen::Vector3d normal(1, 0, 0);  // outward
  const YieldLimits yield{0.002, 0.01};   // stretch, shorten [m]
  // Pressed straight in: the whole patch.
  CHECK(columnYield_m(normal, Eigen::Vector3d(-1, 0, 0), yield, 0) == Approx(0.01));
  // Pressed in at 60 degrees from the normal: half the patch is seen along the push.
  const double c60 = std::cos(M_PI / 3), s60 = std::sin(M_PI / 3);
  CHECK(columnYield_m(normal, Eigen::Vector3d(-c60, s60, 0), yield, 0) == Approx(0.005));
  // Sliding along the skin sweeps no volume: no crush resistance (the shell holds it, not the column).
  CHECK(columnYield_m(normal, Eigen::Vector3d(0, 1, 0), yield, 0) == Approx(0.0).margin(1e-15));
  // Pulled out: the stretch limit; hardening adds what was taken.
  CHECK(columnYield_m(normal, Eigen::Vector3d(1, 0, 0), yield, 0.003) == Approx(0.005));
}

TEST_CASE("Crush column: the return map flows along the displacement and stops at the clamp", "[dynamics]") {
  const Eigen::Vector3d normal(1, 0, 0), original(1, 0, 0);
  const YieldLimits yield{0.01, 0.01};
  const PlasticLaw law{0.0, 0.25, 2.0};  // perfectly plastic, L within [0.25, 2] L0
  const double length0_m = 1.0;
  // Within the elastic range: no flow.
  CHECK(plasticColumnRest(Eigen::Vector3d(0.995, 0, 0), original, original, normal, length0_m, yield, law) ==
        original);
  // Pressed in 0.1 m straight: the rest place follows to 0.01 m (the elastic range) short of the point.
  const Eigen::Vector3d pressed =
      plasticColumnRest(Eigen::Vector3d(0.9, 0, 0), original, original, normal, length0_m, yield, law);
  CHECK(pressed.x() == Approx(0.91));
  CHECK(pressed.y() == Approx(0.0).margin(1e-15));
  // Pressed at 45 degrees: the yield is 0.01 cos 45, and the flow is along the displacement.
  const Eigen::Vector3d slanted(1 - 0.1 / std::sqrt(2.0), 0.1 / std::sqrt(2.0), 0);
  const Eigen::Vector3d moved = plasticColumnRest(slanted, original, original, normal, length0_m, yield, law);
  const double elastic = (slanted - moved).norm();
  CHECK(elastic == Approx(0.01 / std::sqrt(2.0)));
  CHECK((moved - original).normalized().dot((slanted - original).normalized()) == Approx(1.0));
  // Pressed beyond the clamp (crush depth (1 - 0.25) L0): the rest place stops there, rigidly elastic.
  const Eigen::Vector3d deep =
      plasticColumnRest(Eigen::Vector3d(0.1, 0, 0), original, original, normal, length0_m, yield, law);
  CHECK(normal.dot(original - deep) == Approx(0.75));
}

TEST_CASE("Crush column: every point's yield force along a tilted push is crush strength x area x cos(tilt)",
          "[dynamics]") {
  // Every control point of a 60-point hull, pushed at a tilt from its patch normal: the force at which its
  // column flows (the solver's multiplier bound with force-limited constraints, and the return map's
  // limit) is crush_strength x |a . d|, its patch's area seen along the push.
  BodyDescription description;
  description.anchored_columns = true;
  description.max_deviation_m = 0.5;
  const auto settings = makeSettings(sphereHull(60), 100.0, description);
  REQUIRE(settings->anchored_columns);
  for (std::size_t k = 0; k < settings->spokes.size(); ++k) {
    const double area_m2 = settings->tributary_area_m2[k];
    const double compliance = settings->spokes[k].compliance_m_per_N;
    const Eigen::Vector3d& n = settings->spoke_normal[k];
    for (double tilt_deg : {0.0, 30.0, 60.0}) {
      const double t = tilt_deg * M_PI / 180;
      // A push into the patch, tilted about an axis normal to n.
      const Eigen::Vector3d side = n.unitOrthogonal();
      const Eigen::Vector3d push = -std::cos(t) * n + std::sin(t) * side;
      const double force_N = columnYield_m(n, push, settings->spoke_yield[k], 0) / compliance;
      CHECK(force_N == Approx(Material{}.crush_strength_Pa * area_m2 * std::cos(t)).epsilon(1e-9));
    }
  }
}
