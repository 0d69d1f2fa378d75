// The visual constraint (Kenwright 2015, "Visual Constraints") holds under any impulse, however large.
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/deformable_body.hpp>

using namespace deform;
using namespace dynamics_test;

TEST_CASE("the visual constraint holds under any impulse, 1e9 N s included", "[dynamics]") {
  BodyDescription d;
  d.max_deviation_m = 0.1;
  d.max_deviation_overrides = {{0, 0.02}};  // a per-point override: point 0 may move 2 cm only
  const auto settings = makeSettings(sphereHull(42), 1500.0, d);
  REQUIRE(settings->max_deviation_m[0] == 0.02);
  for (double impulse : {1e2, 1e5, 1e9}) {
    DeformableBody body(settings);
    StepInputs inputs;
    double worst_excess = -1;
    for (int k = 0; k < 30; ++k) {
      inputs.impulses.clear();
      if (k % 10 == 0)
        for (uint32_t p : {0u, 7u, 21u})
          inputs.impulses.push_back({p, impulse * Eigen::Vector3d(0.3, -1.0, 0.5 * (k % 20 == 0 ? 1 : -1))});
      body.step(inputs, 1.0 / 60);
      worst_excess = std::max(worst_excess, worstDeviationExcess(*settings, body.state()));
      REQUIRE(largestMagnitude(body.state()) < 1e10);
    }
    INFO("impulse " << impulse << " N s: worst |x - x0| - d_max " << worst_excess << " m");
    CHECK(worst_excess <= 1e-12);
  }
}

TEST_CASE("a region may carry its own material and deviation limit", "[dynamics]") {
  BodyDescription d;
  MaterialRegion bumper;
  bumper.box_m = Aabb{{0.5, -2, -2}, {2, 2, 2}};  // the front (x > 0.5)
  bumper.material.shell_stiffness_N_per_m = 1.0;  // a soft front: edges a 1e8 times more compliant
  bumper.max_deviation_m = 0.05;
  MaterialRegion pillar;
  pillar.points = {0};
  pillar.material.crush_yield_strain = 0.5;
  d.regions = {bumper, pillar};
  const auto settings = makeSettings(sphereHull(42), 1500.0, d);
  REQUIRE(settings->materials.size() == 3);
  std::size_t soft = 0;
  for (const auto& e : settings->edges) {
    const bool front =
        settings->rest_positions_m[e.a].x() >= 0.5 && settings->rest_positions_m[e.b].x() >= 0.5;
    CHECK(e.material == (front ? 1u : 0u));
    CHECK((front ? e.compliance_m_per_N > 1e-3 : e.compliance_m_per_N < 1e-6));
    soft += front;
  }
  CHECK(soft > 0);
  CHECK(settings->spokes[0].material == 2u);
  for (std::size_t i = 0; i < settings->pointCount(); ++i)
    if (settings->rest_positions_m[i].x() >= 0.5) CHECK(settings->max_deviation_m[i] == 0.05);
}
