// Idle cars cost nothing (issue 12; DESIGN.md section 8; DeformationSettings::skip_when_idle): a car
// with nothing near it, once its body has settled, does no deformation solver step at all; a car that
// meets something is solved again. Off, a driving car keeps waking its body.
#include <vehicle/simulation.hpp>

#include "crash_cars.hpp"

#include <catch2/catch.hpp>

using namespace vehicle;
using crash_test::sedan;

namespace {

CarId parkedSedan(Simulation& sim, const Eigen::Vector3d& at_m, bool skip_when_idle) {
  VehicleSettings car;
  car.mass_kg = 1500;
  CarStart start;
  start.position_m = at_m;
  DeformationSettings deformation;
  deformation.skip_when_idle = skip_when_idle;
  return sim.addDeformableCar(sedan(), car, start, deformation);
}

}  // namespace

TEST_CASE("an idle car, once settled, does zero deform steps", "[vehicle][idle]") {
  Simulation sim;
  const CarId idle = parkedSedan(sim, {0, 0, 0}, true);
  sim.run(2.0);  // settles on its suspension; its body falls asleep
  const Simulation::DeformCounts settled = sim.deformCounts(idle);
  REQUIRE(settled.skipped > 0);
  const int steps = sim.run(2.0);
  const Simulation::DeformCounts later = sim.deformCounts(idle);
  CHECK(later.steps == settled.steps);  // not one solver step
  CHECK(later.skipped == settled.skipped + static_cast<uint64_t>(steps));
}

TEST_CASE("without skip_when_idle a driving car's body keeps waking; with it, it is never solved",
          "[vehicle][idle]") {
  // Driving round a bend, the load on the shell changes every step (a parked car's body falls asleep
  // either way).
  Simulation sim;
  const CarId plain = parkedSedan(sim, {0, 0, 0}, false);
  const CarId skipping = parkedSedan(sim, {0, 30, 0}, true);
  DriverInput input;
  input.throttle = 0.4;
  input.steering = 0.3;
  sim.world().car(plain).setInput(input);
  sim.world().car(skipping).setInput(input);
  sim.run(2.0);
  const Simulation::DeformCounts plain_before = sim.deformCounts(plain);
  const Simulation::DeformCounts skipping_before = sim.deformCounts(skipping);
  sim.run(2.0);
  CHECK(sim.deformCounts(plain).steps > plain_before.steps + 100);
  CHECK(sim.deformCounts(skipping).steps == skipping_before.steps);
}

TEST_CASE("a car that meets something is solved again while an idle one is not", "[vehicle][idle]") {
  Simulation sim;
  const CarId idle = parkedSedan(sim, {0, 0, 0}, true);
  const CarId moving = parkedSedan(sim, {0, 10, 0}, true);
  sim.run(2.0);
  const Simulation::DeformCounts idle_before = sim.deformCounts(idle);
  const Simulation::DeformCounts moving_before = sim.deformCounts(moving);
  REQUIRE(sim.body(moving).state().sleeping);
  // A wall appears in front of the second car, which is then pushed into it.
  sim.world().addWall(Pose::yawed({3.0, 10, 0.8}, 0), {0.6, 3, 1.6});
  sim.world().applyImpulse({EntityRef::Kind::Car, moving}, {1500 * 4.0, 0, 0},
                           sim.world().car(moving).bodyPose().position_m);
  sim.run(1.0);
  CHECK(sim.deformCounts(moving).steps > moving_before.steps);
  CHECK(sim.deformCounts(idle).steps == idle_before.steps);
  CHECK(sim.metrics(moving).impacted);
  CHECK(sim.metrics(moving).max_dynamic_crush_m > 0);
}

TEST_CASE("skipping idle cars is deterministic and the same on any thread count", "[vehicle][idle]") {
  auto hashOf = [](int threads) {
    Simulation sim;
    sim.setThreads(threads);
    for (int i = 0; i < 4; ++i) parkedSedan(sim, {0, 6.0 * i, 0}, true);
    sim.run(1.5);
    return sim.stateHash();
  };
  const uint64_t one = hashOf(1);
  CHECK(hashOf(1) == one);
  CHECK(hashOf(2) == one);
}
