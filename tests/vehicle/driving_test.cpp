// The car drives like a car: acceleration, braking, turning, sitting level and still when parked.
#include "driving_helpers.hpp"

#include <vehicle/driver_input.hpp>
#include <vehicle/world.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

using namespace vehicle;
using vehicle_test::sedan;

namespace {

constexpr double kKmh = 1 / 3.6;

}  // namespace

TEST_CASE("sedan accelerates from 0 to 100 km/h in a plausible time", "[vehicle][driving]") {
  World world;
  Car& car = world.car(world.addCar(sedan()));
  DriverInput input;
  input.throttle = 1;
  car.setInput(input);
  double t = 0;
  while (car.forwardSpeed_mps() < 100 * kKmh && t < 30) {
    world.step();
    t += world.fixedDt_s();
  }
  std::printf("[figure] 0-100 km/h: %.2f s\n", t);
  CHECK(t > 5.0);
  CHECK(t < 13.0);
  CHECK(engineMessageCount() == 0);
}

TEST_CASE("sedan brakes from 100 km/h close to the mu g bound", "[vehicle][driving]") {
  World world;
  CarStart start;
  start.speed_mps = 100 * kKmh;
  Car& car = world.car(world.addCar(sedan(), {}, start));
  // Settle at speed for a moment (coasting), then stamp on the brake.
  for (int i = 0; i < 100; ++i) world.step();
  const double v0 = car.forwardSpeed_mps();
  const Eigen::Vector3d x0 = car.bodyPose().position_m;
  DriverInput input;
  input.brake = 1;
  car.setInput(input);
  double t = 0;
  while (car.forwardSpeed_mps() > 0.05 && t < 20) {
    world.step();
    t += world.fixedDt_s();
  }
  const double distance = (car.bodyPose().position_m - x0).norm();
  const double bound = v0 * v0 / (2 * car.settings().tyre.friction_coefficient * 9.81);
  std::printf("[figure] braking from %.1f km/h: %.1f m in %.2f s (mu g bound %.1f m)\n", v0 / kKmh, distance,
              t, bound);
  // Drag and rolling resistance add a little to mu g, so the distance may fall slightly short of it.
  CHECK(distance >= bound * 0.95);
  CHECK(distance <= bound * 1.25);
  CHECK(std::abs(vehicle_test::heading_rad(car.bodyPose())) < 0.05);
}

TEST_CASE("sedan turns with the kinematic radius at low speed", "[vehicle][driving]") {
  World world;
  Car& car = world.car(world.addCar(sedan()));
  SpeedController speed;
  const double steer = 0.2;
  const double dt = world.fixedDt_s();
  for (int i = 0; i < 15 * 500; ++i) {
    DriverInput input = speed.update(5.0, car.forwardSpeed_mps(), dt);
    input.steer_angle_rad = steer;
    car.setInput(input);
    world.step();
  }
  // Radius of the rear axle's middle, which the kinematic (Ackermann) radius L / tan(delta) refers to.
  double rear_x = 0;
  int rears = 0;
  for (const auto& w : car.wheelSettings())
    if (!w.steered) rear_x += w.centre_m.x(), ++rears;
  const Pose body = car.bodyPose();
  const Eigen::Vector3d rear_axle =
      body.orientation * (Eigen::Vector3d(rear_x / rears, 0, 0) - car.centreOfMass_m());
  const Eigen::Vector3d omega = car.angularVelocity_rad_s();
  const Eigen::Vector3d v_rear = car.velocity_mps() + omega.cross(rear_axle);
  const double radius = v_rear.head<2>().norm() / std::abs(omega.z());
  const double kinematic = car.wheelbase_m() / std::tan(steer);
  std::printf("[figure] turning at %.1f m/s, steer %.2f rad: radius %.2f m (L/tan(delta) = %.2f m)\n",
              car.forwardSpeed_mps(), steer, radius, kinematic);
  CHECK(omega.z() > 0);  // a left turn
  CHECK(radius == Approx(kinematic).epsilon(0.08));
}

TEST_CASE("parked sedan sits level on its suspension and does not creep or jitter", "[vehicle][driving]") {
  for (int mode = 0; mode < 3; ++mode) {  // 0: handbrake, 1: foot brake, 2: no input at all
    World world;
    Car& car = world.car(world.addCar(sedan()));
    DriverInput input;
    input.handbrake = mode == 0;
    input.brake = mode == 1 ? 1.0 : 0.0;
    car.setInput(input);
    for (int i = 0; i < 500; ++i) world.step();  // 1 s to settle
    const Pose settled = car.bodyPose();
    double peak_speed = 0, peak_spin = 0;
    for (int i = 0; i < 10 * 500; ++i) {
      world.step();
      peak_speed = std::max(peak_speed, car.velocity_mps().norm());
      peak_spin = std::max(peak_spin, car.angularVelocity_rad_s().norm());
    }
    const Pose rest = car.bodyPose();
    const double drift = (rest.position_m - settled.position_m).norm();
    const double pitch_deg = vehicle_test::pitch_rad(rest) * 180 / std::numbers::pi;
    const double roll_deg = vehicle_test::roll_rad(rest) * 180 / std::numbers::pi;
    std::printf(
        "[figure] parked (%s): pitch %.4f deg, roll %.4f deg, drift over 10 s %.2e m, peak speed %.2e m/s, "
        "peak rate %.2e rad/s\n",
        mode == 0   ? "handbrake"
        : mode == 1 ? "foot brake"
                    : "no input",
        pitch_deg, roll_deg, drift, peak_speed, peak_spin);
    CHECK(std::abs(pitch_deg) < 0.25);
    CHECK(std::abs(roll_deg) < 0.05);
    CHECK(drift < 1e-3);
    CHECK(peak_speed < 1e-3);
    CHECK(peak_spin < 1e-3);
    // Wheels ride at their design centres: the compression equals the static one within 5 mm.
    for (std::size_t i = 0; i < car.wheels().size(); ++i) {
      const Eigen::Vector3d hub = car.vehiclePose().toLocal(car.wheelPose(i).position_m);
      CHECK((hub - car.wheelSettings()[i].centre_m).norm() < 0.005);
    }
  }
}
