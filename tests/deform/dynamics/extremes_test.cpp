// Stability at the extremes (DESIGN.md section 7): no NaN, no value beyond 1e10, deformation bounded by
// the visual constraint, for time steps 1e-5 .. 0.1 s, substeps 1 .. 64, compliance 0 .. 1 m/N, yield
// 0 .. 1, a 1e4 mass ratio, and 4 or about 4,000 control points. Bad time steps are refused.
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/deformable_body.hpp>
#include <deform/error.hpp>
#include <deform/masses.hpp>

#include <limits>

using namespace deform;
using namespace dynamics_test;

namespace {

/// A rough ride: an impulse, a sphere pushed into the side, gravity, a hard brake and a spin.
StepInputs roughInputs(const BodySettings& settings, int step) {
  StepInputs in;
  if (step % 5 == 0) in.impulses.push_back({0, Eigen::Vector3d(-2e4, 1e3, 5e3)});
  in.contacts.emplace_back(SphereShape{settings.core_m + Eigen::Vector3d(1.3, 0, 0), 0.5});
  in.chassis.gravity_mps2 = {0, 0, -9.81};
  in.chassis.acceleration_mps2 = {-80.0, 0, 0};
  in.chassis.angular_velocity_radps = {0, 0, 6.0};
  in.chassis.angular_acceleration_radps2 = {0, 40.0, 0};
  return in;
}

void ride(const std::shared_ptr<const BodySettings>& settings, const SolverParams& params, double dt,
          int steps) {
  DeformableBody body(settings, params);
  for (int k = 0; k < steps; ++k) {
    body.step(roughInputs(*settings, k), dt);
    const double largest = largestMagnitude(body.state());
    const double excess = worstDeviationExcess(*settings, body.state());
    if (!(largest < 1e10) || !(excess <= 1e-9)) {
      FAIL("step " << k << ": largest value " << largest << ", deviation excess " << excess);
    }
  }
  CHECK(std::isfinite(body.state().plastic_work_J));
}

}  // namespace

TEST_CASE("extremes of time step, substeps, compliance and yield stay finite and bounded",
          "[dynamics][extreme]") {
  const ControlMesh mesh = sphereHull(42);
  for (double compliance : {0.0, 1e-6, 1.0})
    for (double yield : {0.0, 1.0}) {
      BodyDescription d;
      d.max_deviation_m = 0.25;
      const auto settings =
          makeSettings(mesh, 1500.0, d, UniformMaterial{compliance, compliance, compliance, yield});
      for (double dt : {1e-5, 1.0 / 60, 0.1})
        for (uint32_t substeps : {1u, 64u}) {
          SolverParams params;
          params.substeps = substeps;
          params.iterations = substeps == 1 ? 8 : 1;
          INFO("compliance " << compliance << ", yield " << yield << ", dt " << dt << ", substeps "
                             << substeps);
          ride(settings, params, dt, 12);
        }
    }
}

TEST_CASE("a mass ratio of 1e4 between control points stays finite and bounded", "[dynamics][extreme]") {
  const ControlMesh mesh = sphereHull(42);
  MassSplit masses = distributeMass(mesh, 1500.0);
  for (std::size_t i = 0; i < masses.point_mass_kg.size(); i += 2) masses.point_mass_kg[i] *= 1e4;
  const auto settings =
      std::make_shared<const BodySettings>(createBodySettings(mesh, masses, BodyDescription{}));
  for (double dt : {1e-5, 1.0 / 60, 0.1}) {
    SolverParams params;
    params.substeps = 8;
    ride(settings, params, dt, 20);
  }
}

TEST_CASE("4 and about 4,000 control points stay finite and bounded", "[dynamics][extreme]") {
  for (std::size_t count : {4u, 4000u}) {
    const auto settings = makeSettings(sphereHull(count), 1500.0, BodyDescription{});
    INFO(count << " control points");
    for (double dt : {1e-5, 0.1}) {
      SolverParams params;
      params.substeps = 4;
      ride(settings, params, dt, 4);
    }
  }
}

TEST_CASE("a time step of zero, negative or not finite is refused naming dt_s", "[dynamics][extreme]") {
  const auto settings = makeSettings(icosahedron(), 1000.0, BodyDescription{});
  DeformableBody body(settings);
  for (double dt :
       {0.0, -0.01, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    CHECK_THROWS_WITH(body.step({}, dt), Catch::Contains("dt_s"));
  CHECK(hashState(body.state()) == hashState(restState(*settings)));  // nothing half-done
  SolverParams params;
  params.substeps = 0;
  CHECK_THROWS_WITH(DeformableBody(settings, params), Catch::Contains("substeps"));
  StepInputs bad;
  bad.impulses.push_back({99, {1, 0, 0}});
  CHECK_THROWS_WITH(body.step(bad, 0.01), Catch::Contains("impulses[0]"));
}
