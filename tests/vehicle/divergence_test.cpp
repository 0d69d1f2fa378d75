// Bad input to the library's world (a non-finite force or impulse) is refused before ODE sees it; a run
// that has not diverged says nothing diverged (CrashMetrics::diverged_what).
#include <vehicle/simulation.hpp>

#include "crash_cars.hpp"

#include <deform/builtin_meshes.hpp>
#include <deform/error.hpp>

#include <catch2/catch.hpp>

#include <limits>

using namespace vehicle;
using crash_test::sedan;

TEST_CASE("A non-finite force or impulse on a body is refused before ODE sees it", "[crush]") {
  // ODE aborts the process on a NaN; the library refuses it as bad input instead.
  Simulation sim;
  const CarId id = sim.addDeformableCar(sedan(), {}, {}, {});
  const EntityRef car{EntityRef::Kind::Car, id};
  const Eigen::Vector3d at = sim.world().car(id).bodyPose().position_m;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(sim.world().applyImpulse(car, {nan, 0, 0}, at), deform::InputError);
  CHECK_THROWS_AS(sim.world().applyImpulse(car, {1, 0, 0}, at, {0, 0, nan}), deform::InputError);
  CHECK_THROWS_AS(sim.world().addForce(car, {0, std::numeric_limits<double>::infinity(), 0}, at),
                  deform::InputError);
  sim.run(0.1);
  CHECK_FALSE(sim.metrics(id).diverged);
  CHECK(sim.metrics(id).diverged_what.empty());
}
