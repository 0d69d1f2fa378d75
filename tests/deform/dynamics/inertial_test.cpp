// Secondary motion (Kenwright 2015, "Experimental Results"): the chassis's acceleration and rotation act
// on the control points as inertial forces in the vehicle frame, scaled by inertial_scale.
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/deformable_body.hpp>

using namespace deform;
using namespace dynamics_test;

namespace {

/// Mean x displacement [m] after 1 s of a steady acceleration a_x.
double meanLagX(double inertial_scale, double accel_mps2) {
  BodyDescription d;
  const auto settings = makeSettings(icosahedron(), 1000.0, d, elasticMaterial(1e-5));
  SolverParams params;
  params.inertial_scale = inertial_scale;
  params.damping_per_s = 30;
  params.sleep_delay_s = -1;
  DeformableBody body(settings, params);
  StepInputs in;
  in.chassis.acceleration_mps2 = {accel_mps2, 0, 0};
  for (int k = 0; k < 60; ++k) body.step(in, 1.0 / 60);
  double sum = 0;
  for (std::size_t i = 0; i < settings->pointCount(); ++i)
    sum += body.state().positions_m[i].x() - settings->rest_positions_m[i].x();
  return sum / static_cast<double>(settings->pointCount());
}

}  // namespace

TEST_CASE("braking throws the body forward, in proportion to the inertial scale; 0 disables it",
          "[dynamics]") {
  const double full = meanLagX(1.0, -9.0), half = meanLagX(0.5, -9.0);
  CHECK(full > 0);  // the chassis decelerates: the body leans forward (+x)
  CHECK(half == Approx(0.5 * full).epsilon(0.02));
  CHECK(meanLagX(0.0, -9.0) == 0.0);
}

TEST_CASE("a spinning chassis flings the control points outwards", "[dynamics]") {
  BodyDescription d;
  const auto settings = makeSettings(icosahedron(), 1000.0, d, elasticMaterial(1e-5));
  SolverParams params;
  params.damping_per_s = 30;
  params.sleep_delay_s = -1;
  DeformableBody body(settings, params);
  StepInputs in;
  in.chassis.angular_velocity_radps = {0, 0, 10};
  for (int k = 0; k < 60; ++k) body.step(in, 1.0 / 60);
  CHECK(meanRadius(*settings, body.state()) > 1.0);
}
