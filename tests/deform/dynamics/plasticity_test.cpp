// Elastic below yield, a permanent set above it (Kenwright 2015, "Dynamics"), bounded by the visual
// constraint. The icosahedron pressed on every vertex by a plate is a uniform compression: every edge,
// spoke and bend has the same strain -s = -delta / R, so the answer is exact. Flowing at the yield strain
// e_y, the rest length ends where (l - L) / L = -e_y, i.e. L = l / (1 - e_y), and the set after release is
//   R - L = R (s - e_y) / (1 - e_y)          (the excess over yield).
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/deformable_body.hpp>

using namespace deform;
using namespace dynamics_test;

namespace {

constexpr double kRadius_m = 1.0;
constexpr double kDt_s = 1.0 / 240;

/// Presses every vertex in to kRadius_m - delta over 0.5 s (quasi-static), holds 0.25 s, releases and
/// lets the body settle for 2 s.
DeformableBody pressAndRelease(const std::shared_ptr<const BodySettings>& settings, double delta_m) {
  SolverParams params;
  params.substeps = 4;
  params.damping_per_s = 20.0;
  params.sleep_delay_s = -1;  // never sleep: the test wants every step simulated
  DeformableBody body(settings, params);
  StepInputs inputs;
  const int press_steps = 120, hold_steps = 60, settle_steps = 480;
  for (int k = 0; k < press_steps + hold_steps; ++k) {
    const double reach = kRadius_m - delta_m * std::min(1.0, (k + 1.0) / press_steps);
    inputs.contacts = radialPlates(*settings, reach);
    inputs.contact_friction = 1.0;  // the plates hold the points: no sideways buckling of the shell
    body.step(inputs, kDt_s);
  }
  inputs.contacts.clear();
  for (int k = 0; k < settle_steps; ++k) body.step(inputs, kDt_s);
  return body;
}

BodyDescription description(double max_deviation_m = 0.5) {
  BodyDescription d;
  d.max_deviation_m = max_deviation_m;
  return d;
}

UniformMaterial yieldingAt(double yield_strain) {
  return {1e-6, 1e-5, 1e-5, yield_strain};
}

}  // namespace

TEST_CASE("below yield a pressed body returns to its rest shape and keeps its rest lengths", "[dynamics]") {
  const auto settings = makeSettings(icosahedron(kRadius_m), 1000.0, description(), yieldingAt(0.02));
  DeformableBody body = pressAndRelease(settings, 0.015);  // strain 1.5 % < 2 %
  const BodyState& s = body.state();
  // Tolerance 0.05 mm: what 2 s of damping at 20/s leaves of the release.
  WARN("1.5 cm press below yield: back to rest within " << maxDeviation(*settings, s) * 1e3 << " mm");
  CHECK(maxDeviation(*settings, s) < 5e-5);
  CHECK(s.edge_rest_m == settings->edge_rest_m);  // bit-identical: no flow at all
  CHECK(s.spoke_rest_m == settings->spoke_rest_m);
  CHECK(s.bend_rest_m == settings->bend_rest_m);
  CHECK(s.plastic_work_J == 0.0);
}

TEST_CASE("above yield the permanent set matches the excess over yield and grows with the press",
          "[dynamics]") {
  const double yield = 0.02;
  const auto settings = makeSettings(icosahedron(kRadius_m), 1000.0, description(), yieldingAt(yield));
  double previous_set = 0, previous_work = 0;
  for (double delta : {0.05, 0.10, 0.20}) {
    DeformableBody body = pressAndRelease(settings, delta);
    const double set = kRadius_m - meanRadius(*settings, body.state());
    const double s = delta / kRadius_m;
    const double expected = kRadius_m * (s - yield);  // the elastic range is yield x L0
    INFO("press " << delta << " m: set " << set << " m, expected " << expected << " m, plastic work "
                  << body.state().plastic_work_J << " J");
    WARN("press " << delta << " m: set " << set * 1e3 << " mm, excess over yield " << expected * 1e3
                  << " mm (" << (set / expected - 1) * 100 << " %)");
    CHECK(set == Approx(expected).epsilon(0.02));  // within 2 % of the excess over yield
    // Uniform: every point has the same set (1 %).
    for (const auto& p : body.state().positions_m)
      CHECK((p - settings->core_m).norm() == Approx(kRadius_m - set).epsilon(0.01));
    CHECK(set > previous_set);
    CHECK(body.state().plastic_work_J > previous_work);
    previous_set = set;
    previous_work = body.state().plastic_work_J;
  }
}

TEST_CASE("the permanent set is bounded by the visual constraint", "[dynamics]") {
  const double max_deviation = 0.04;
  const auto settings =
      makeSettings(icosahedron(kRadius_m), 1000.0, description(max_deviation), yieldingAt(0.02));
  DeformableBody body = pressAndRelease(settings, 0.3);  // pressed far past the visual limit
  const double set = kRadius_m - meanRadius(*settings, body.state());
  INFO("set " << set << " m, limit " << max_deviation << " m");
  WARN("press 0.3 m with a 4 cm visual limit: set " << set * 1e3 << " mm, largest deviation "
                                                    << maxDeviation(*settings, body.state()) * 1e3 << " mm");
  CHECK(set > 0.5 * max_deviation);
  CHECK(maxDeviation(*settings, body.state()) <= max_deviation * (1 + 1e-12));
}

TEST_CASE("rest lengths stay within their clamp under repeated crushing", "[dynamics]") {
  BodyDescription d = description(5.0);
  d.material.min_rest_fraction = 0.6;
  const auto settings =
      makeSettings(icosahedron(kRadius_m), 1000.0, d, yieldingAt(0.0));  // every strain flows
  SolverParams params;
  params.sleep_delay_s = -1;
  DeformableBody body(settings, params);
  StepInputs inputs;
  for (int hit = 0; hit < 5; ++hit) {
    inputs.contacts = radialPlates(*settings, 0.05);  // crush to 5 % of the radius
    for (int k = 0; k < 20; ++k) body.step(inputs, kDt_s);
    inputs.contacts.clear();
    for (int k = 0; k < 20; ++k) body.step(inputs, kDt_s);
  }
  const BodyState& s = body.state();
  for (std::size_t k = 0; k < s.spoke_rest_m.size(); ++k)
    CHECK(s.spoke_rest_m[k] >= 0.6 * settings->spoke_rest_m[k] * (1 - 1e-12));
  for (std::size_t k = 0; k < s.edge_rest_m.size(); ++k)
    CHECK(s.edge_rest_m[k] >= 0.6 * settings->edge_rest_m[k] * (1 - 1e-12));
}
