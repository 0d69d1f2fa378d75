// The crush coupling shares the chassis's motion with the shell's points once: a car that brakes and
// spins on open ground, touching nothing, changes its whole momentum (chassis and every control point) by
// exactly the impulse of the forces on it, and loses exactly the kinetic energy its tyres take.
#include <vehicle/simulation.hpp>

#include "crash_cars.hpp"

#include <deform/deformable_body.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

using namespace vehicle;

namespace {

/// The whole car's momentum in the world: the ODE chassis and the control points moving with its frame
/// [N s].
Eigen::Vector3d wholeMomentum(const Simulation& sim, CarId id) {
  const Car& car = sim.world().car(id);
  const Eigen::Quaterniond to_world = car.vehiclePose().orientation;
  const Eigen::Vector3d v = to_world.conjugate() * car.velocity_mps();
  const Eigen::Vector3d w = to_world.conjugate() * car.angularVelocity_rad_s();
  const deform::DeformableBody& body = sim.body(id);
  const std::vector<double>& m = body.settings().mass_kg;
  Eigen::Vector3d p = car.chassisMass_kg() * v;
  for (std::size_t i = 0; i < m.size(); ++i)
    p += m[i] *
         (v + w.cross(body.state().positions_m[i] - car.centreOfMass_m()) + body.state().velocities_mps[i]);
  return to_world * p;
}

}  // namespace

TEST_CASE("Crush coupling: a braking, spinning car's momentum changes by its tyres' and weight's impulse",
          "[crush][momentum]") {
  Simulation sim;
  CarStart start;
  start.speed_mps = 60 * crash_test::kKmh;
  const CarId id = sim.addDeformableCar(crash_test::sedan(), {}, start, DeformationSettings{});
  Car& car = sim.world().car(id);
  DriverInput input;
  input.steering = 0.8;  // hard over: the car yaws and slides
  input.brake = 0.7;
  car.setInput(input);
  const double dt = sim.world().fixedDt_s();
  const VehicleSettings& vs = car.settings();
  double worst_relative = 0, impulse_sum = 0, error_sum = 0, largest_yaw = 0;
  for (int step = 0; step < 750; ++step) {  // 1.5 s at 500 Hz
    const Eigen::Vector3d before = wholeMomentum(sim, id);
    const Eigen::Vector3d v = car.velocity_mps();
    sim.step();
    // The forces of this step: the tyres (ODE's, at their contact points), the whole car's weight, the
    // air's drag at the start of the step.
    Eigen::Vector3d force = car.mass_kg() * sim.world().settings().gravity_mps2 -
                            0.5 * vs.air_density_kg_m3 * vs.drag_area_m2 * v.norm() * v;
    for (const WheelState& w : car.wheels())
      if (w.in_contact) force += w.force_N;
    const Eigen::Vector3d impulse = force * dt;
    const Eigen::Vector3d change = wholeMomentum(sim, id) - before;
    const Eigen::Vector3d horizontal_error(change.x() - impulse.x(), change.y() - impulse.y(), 0);
    const double horizontal_impulse = std::hypot(impulse.x(), impulse.y());
    if (horizontal_impulse > 1.0)
      worst_relative = std::max(worst_relative, horizontal_error.norm() / horizontal_impulse);
    impulse_sum += horizontal_impulse;
    error_sum += horizontal_error.norm();
    largest_yaw = std::max(largest_yaw, std::abs(car.angularVelocity_rad_s().z()));
  }
  std::printf(
      "[figure] braking and spinning crush car: momentum error %.2e of the impulse (worst step "
      "%.2e), yaw up to %.2f rad/s\n",
      error_sum / impulse_sum, worst_relative, largest_yaw);
  REQUIRE(largest_yaw > 0.3);             // it did spin
  CHECK(error_sum < 1e-3 * impulse_sum);  // the shell counted once: 8 % when it was shared twice
  CHECK(worst_relative < 5e-3);           // asleep too: 11 % when a sleeping shell held a kinematic core
}
