// Sleep (DESIGN.md section 8): a resting body costs (nearly) nothing per step and wakes on contact.
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/deformable_body.hpp>

#include <chrono>

using namespace deform;
using namespace dynamics_test;

namespace {

/// Median-free cheap timing: the mean over `steps` calls [s per step].
double secondsPerStep(DeformableBody& body, const StepInputs& inputs, int steps) {
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) body.step(inputs, 1.0 / 60);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / steps;
}

}  // namespace

TEST_CASE("a resting body falls asleep, costs nearly nothing and wakes on contact", "[dynamics]") {
  const auto settings = makeSettings(sphereHull(4000), 1500.0, BodyDescription{});
  SolverParams params;
  params.sleep_delay_s = 0.05;
  DeformableBody body(settings, params);
  StepInputs nothing;
  nothing.chassis.gravity_mps2 = {0, 0, -9.81};
  // Awake: gravity sags the body, then it settles and sleeps.
  const double awake_s = secondsPerStep(body, nothing, 3);
  CHECK_FALSE(body.state().sleeping);
  for (int k = 0; k < 600 && !body.state().sleeping; ++k) body.step(nothing, 1.0 / 60);
  REQUIRE(body.state().sleeping);
  const BodyState at_sleep = body.state();
  const double asleep_s = secondsPerStep(body, nothing, 2000);
  WARN("4,000 control points: awake " << awake_s * 1e6 << " us/step, asleep " << asleep_s * 1e9
                                      << " ns/step");
  CHECK(asleep_s < awake_s / 100);
  CHECK(body.step(nothing, 1.0 / 60).asleep);
  // Only the clock moved.
  BodyState now = body.state();
  CHECK(now.time_s > at_sleep.time_s);
  now.time_s = at_sleep.time_s;
  CHECK(hashState(now) == hashState(at_sleep));

  // A contact wakes it and dents it.
  StepInputs hit = nothing;
  hit.contacts.push_back(SphereShape{settings->core_m + Eigen::Vector3d(1.2, 0, 0), 0.3});
  const StepReport report = body.step(hit, 1.0 / 60);
  CHECK_FALSE(report.asleep);
  CHECK(report.contact_points > 0);
  CHECK_FALSE(body.state().sleeping);
  // A change of the inertial load wakes a sleeping body too.
  for (int k = 0; k < 600 && !body.state().sleeping; ++k) body.step(nothing, 1.0 / 60);
  REQUIRE(body.state().sleeping);
  StepInputs braking = nothing;
  braking.chassis.acceleration_mps2 = {-8, 0, 0};
  CHECK_FALSE(body.step(braking, 1.0 / 60).asleep);
}
