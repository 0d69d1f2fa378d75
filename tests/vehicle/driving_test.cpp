// The car drives like a car: acceleration, braking, turning, sitting level and still when parked.
#include "crash_cars.hpp"
#include "driving_helpers.hpp"

#include <vehicle/driver_input.hpp>
#include <vehicle/world.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

using namespace vehicle;
using crash_test::kKmh;
using vehicle_test::drivingSedan;

namespace {}  // namespace

TEST_CASE("sedan accelerates from 0 to 100 km/h in a plausible time", "[vehicle][driving]") {
  World world;
  Car& car = world.car(world.addCar(drivingSedan()));
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
  Car& car = world.car(world.addCar(drivingSedan(), {}, start));
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
  Car& car = world.car(world.addCar(drivingSedan()));
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
    Car& car = world.car(world.addCar(drivingSedan()));
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

TEST_CASE("a car stopped by its brakes settles and stays put, also on a 10 % slope", "[vehicle][driving]") {
  struct Case {
    const char* name;
    double rate_hz;
    bool slope, handbrake;
  };
  const Case cases[] = {{"stopped on the flat, handbrake, 240 Hz", 240, false, true},
                        {"stopped on the flat, handbrake, 500 Hz", 500, false, true},
                        {"stopped on the flat, handbrake, 2000 Hz", 2000, false, true},
                        {"10 % slope, handbrake", 500, true, true},
                        {"10 % slope, foot brake", 500, true, false}};
  for (const Case& c : cases) {
    WorldSettings settings;
    settings.physics_rate_hz = c.rate_hz;
    settings.ground = !c.slope;
    World world(settings);
    CarStart start;
    const double slope = std::atan(0.1);
    if (c.slope) {  // a road tilted up along +X; the car is dropped on it
      world.addWall(Pose{{0, 0, 0}, Eigen::Quaterniond(Eigen::AngleAxisd(-slope, Eigen::Vector3d::UnitY()))},
                    {100, 20, 1});
      start.position_m = {0, 0, 0.5 / std::cos(slope) + 0.2};
    }
    Car& car = world.car(world.addCar(drivingSedan(), {}, start));
    SpeedController speed;
    const double dt = world.fixedDt_s();
    const int second = static_cast<int>(c.rate_hz);
    if (!c.slope) {  // drive at 3 m/s first
      for (int i = 0; i < 3 * second; ++i) {
        car.setInput(speed.update(3.0, car.forwardSpeed_mps(), dt));
        world.step();
      }
    }
    DriverInput park;
    park.handbrake = c.handbrake;
    park.brake = c.handbrake ? 0.0 : 1.0;
    car.setInput(park);
    for (int i = 0; i < 3 * second; ++i) world.step();  // stop and settle
    const Pose settled = car.bodyPose();
    double peak_speed = 0;
    for (int i = 0; i < 10 * second; ++i) {
      world.step();
      peak_speed = std::max(peak_speed, car.velocity_mps().norm());
    }
    const double drift = (car.bodyPose().position_m - settled.position_m).norm();
    const double pitch_deg = vehicle_test::pitch_rad(car.bodyPose()) * 180 / std::numbers::pi;
    std::printf("[figure] %s: pitch %.3f deg, drift over 10 s %.2e m, peak speed %.2e m/s\n", c.name,
                pitch_deg, drift, peak_speed);
    CAPTURE(c.name);
    CHECK(drift < 1e-3);
    CHECK(peak_speed < 1e-3);
    if (!c.slope) CHECK(std::abs(pitch_deg) < 0.25);
    if (c.slope) CHECK(pitch_deg == Approx(slope * 180 / std::numbers::pi).margin(0.5));
  }
}

TEST_CASE("driving figures do not depend on the physics rate", "[vehicle][driving]") {
  auto zeroTo100 = [](double rate_hz) {
    WorldSettings settings;
    settings.physics_rate_hz = rate_hz;
    World world(settings);
    Car& car = world.car(world.addCar(drivingSedan()));
    DriverInput input;
    input.throttle = 1;
    car.setInput(input);
    while (car.forwardSpeed_mps() < 100 * kKmh && world.time_s() < 30) world.step();
    return world.time_s();
  };
  auto brakingDistance = [](double rate_hz) {
    WorldSettings settings;
    settings.physics_rate_hz = rate_hz;
    World world(settings);
    CarStart start;
    start.speed_mps = 100 * kKmh;
    Car& car = world.car(world.addCar(drivingSedan(), {}, start));
    DriverInput input;
    input.brake = 1;
    car.setInput(input);
    while (car.forwardSpeed_mps() > 0.05 && world.time_s() < 20) world.step();
    return car.bodyPose().position_m.x();
  };
  const double t500 = zeroTo100(500), d500 = brakingDistance(500);
  for (double rate : {240.0, 2000.0}) {
    const double t = zeroTo100(rate), d = brakingDistance(rate);
    std::printf("[figure] at %.0f Hz: 0-100 km/h %.2f s (500 Hz: %.2f s), braking %.2f m (500 Hz: %.2f m)\n",
                rate, t, t500, d, d500);
    CHECK(t == Approx(t500).epsilon(0.02));
    CHECK(d == Approx(d500).epsilon(0.02));
  }
}

TEST_CASE("wheel state for drawing: rolling, steering, riding", "[vehicle][driving]") {
  World world;
  CarStart start;
  start.speed_mps = 10;
  Car& car = world.car(world.addCar(drivingSedan(), {}, start));
  DriverInput input;
  input.throttle = 0.15;
  input.steering = 0.2;  // 0.12 rad: a 23 m radius, 0.45 g at 10 m/s
  car.setInput(input);
  std::vector<double> previous_rotation;
  for (const auto& w : car.wheels()) previous_rotation.push_back(w.rotation_rad);
  for (int i = 0; i < 250; ++i) world.step();
  CHECK(car.steerAngle_rad() == Approx(0.2 * car.settings().max_steer_rad));
  for (std::size_t i = 0; i < car.wheels().size(); ++i) {
    const WheelState& w = car.wheels()[i];
    const WheelSettings& ws = car.wheelSettings()[i];
    CHECK(w.in_contact);
    CHECK(w.tyre.spin_rad_s * ws.radius_m == Approx(car.forwardSpeed_mps()).epsilon(0.1));
    CHECK(w.rotation_rad >= 0);
    CHECK(w.rotation_rad < 2 * std::numbers::pi);
    CHECK(w.compression_m > 0.03);
    CHECK(w.compression_m < ws.max_compression_m);
    if (ws.steered)
      CHECK(w.steer_angle_rad > 0);
    else
      CHECK(w.steer_angle_rad == 0);
    // The drawn hub sits on the road: radius above the contact point.
    const Pose hub = car.wheelPose(i);
    CHECK((hub.position_m - w.contact_point_m).norm() == Approx(ws.radius_m).epsilon(0.05));
  }
  // Turning left: the inner (left) front wheel steers more than the outer one (Ackermann).
  double left = 0, right = 0;
  for (std::size_t i = 0; i < car.wheels().size(); ++i) {
    if (!car.wheelSettings()[i].steered) continue;
    (car.wheelSettings()[i].centre_m.y() > 0 ? left : right) = car.wheels()[i].steer_angle_rad;
  }
  CHECK(left > right);
  // Leaning out of the turn: the right (outer) wheels carry more.
  double load_left = 0, load_right = 0;
  for (std::size_t i = 0; i < car.wheels().size(); ++i)
    (car.wheelSettings()[i].centre_m.y() > 0 ? load_left : load_right) += car.wheels()[i].normal_load_N;
  CHECK(load_right > load_left);
}

TEST_CASE("coasting and bouncing never create energy", "[vehicle][driving]") {
  World world;
  CarStart start;
  start.speed_mps = 20;
  start.position_m = {0, 0, 0.3};  // dropped from 30 cm while rolling
  Car& car = world.car(world.addCar(drivingSedan(), {}, start));
  auto energy = [&] {
    const Eigen::Vector3d w = car.angularVelocity_rad_s();
    const Eigen::Matrix3d r = car.bodyPose().orientation.toRotationMatrix();
    const Eigen::Matrix3d inertia_world = r * car.inertia_kg_m2() * r.transpose();
    double e = 0.5 * car.mass_kg() * car.velocity_mps().squaredNorm() + 0.5 * w.dot(inertia_world * w) +
               car.mass_kg() * 9.81 * car.bodyPose().position_m.z();
    for (std::size_t i = 0; i < car.wheels().size(); ++i) {
      const double spin = car.wheels()[i].tyre.spin_rad_s;
      e += 0.5 * car.wheelSettings()[i].inertia_kg_m2 * spin * spin;
      // Spring energy of the suspension.
      const double c = car.wheels()[i].compression_m;
      e += 0.5 * car.wheelSettings()[i].spring_N_per_m * c * c;
    }
    return e;
  };
  const double e0 = energy();
  double highest = e0, previous = e0;
  for (int i = 0; i < 5000; ++i) {
    DriverInput input;
    input.steering = 0.1 * std::sin(0.002 * i);
    car.setInput(input);
    world.step();
    const double e = energy();
    highest = std::max(highest, e);
    previous = e;
  }
  std::printf("[figure] coasting 10 s from 20 m/s: energy %.0f J -> %.0f J, highest %.0f J\n", e0, previous,
              highest);
  CHECK(highest <= e0 * 1.001);
  CHECK(previous < e0);
}

TEST_CASE("a long parked run stays put and finite", "[vehicle][driving]") {
  World world;
  Car& car = world.car(world.addCar(drivingSedan()));
  DriverInput input;
  input.handbrake = true;
  car.setInput(input);
  const Eigen::Vector3d start = car.bodyPose().position_m;
  for (int i = 0; i < 100000; ++i) world.step();
  CHECK((car.bodyPose().position_m - start).norm() < 1e-6);
  for (const auto& w : car.wheels()) CHECK(std::isfinite(w.tyre.lateral_deflection_m));
}

TEST_CASE("from 1 kg to 40 t: scaled settings sit level and drive", "[vehicle][driving]") {
  for (double mass : {1.0, 40000.0}) {
    World world;
    VehicleSettings settings;
    settings.wheels = wheelsFromModel(settings, drivingSedan());
    settings = settingsForMass(settings, mass);
    Car& car = world.car(world.addCar(drivingSedan(), settings));
    DriverInput input;
    input.throttle = 0.5;
    car.setInput(input);
    for (int i = 0; i < 2500; ++i) world.step();
    CAPTURE(mass);
    CHECK(car.forwardSpeed_mps() > 8);  // the same 9.5 m/s whatever the mass
    CHECK(std::abs(vehicle_test::roll_rad(car.bodyPose())) < 0.01);
    input = {};
    input.brake = 1;
    car.setInput(input);
    for (int i = 0; i < 2500; ++i) world.step();
    CHECK(std::abs(car.forwardSpeed_mps()) < 0.01);
    CHECK(std::abs(vehicle_test::pitch_rad(car.bodyPose())) < 0.01);
  }
}

TEST_CASE("coasting slows by drag and rolling resistance only", "[vehicle][driving]") {
  World world;
  CarStart start;
  start.speed_mps = 100 * kKmh;
  Car& car = world.car(world.addCar(drivingSedan(), {}, start));
  const VehicleSettings& s = car.settings();
  // The same deceleration integrated alone: m dv/dt = -1/2 rho C_d A v^2 - C_rr m g.
  double v = start.speed_mps;
  const double dt = world.fixedDt_s();
  for (int i = 0; i < 10 * 500; ++i) {
    world.step();
    v -= dt *
         (0.5 * s.air_density_kg_m3 * s.drag_area_m2 * v * v / s.mass_kg + s.tyre.rolling_resistance * 9.81);
  }
  std::printf(
      "[figure] coasting 10 s from 100 km/h: %.2f m/s (drag and rolling resistance alone: %.2f m/s)\n",
      car.forwardSpeed_mps(), v);
  CHECK(car.forwardSpeed_mps() == Approx(v).epsilon(0.01));
}

TEST_CASE("reverse gear drives backwards; the handbrake holds against the engine", "[vehicle][driving]") {
  World world;
  Car& car = world.car(world.addCar(drivingSedan()));
  DriverInput input;
  input.throttle = 0.3;
  input.reverse = true;
  car.setInput(input);
  for (int i = 0; i < 1000; ++i) world.step();
  CHECK(car.forwardSpeed_mps() < -1.5);
  input = {};
  input.brake = 1;
  car.setInput(input);
  for (int i = 0; i < 1500; ++i) world.step();
  CHECK(std::abs(car.forwardSpeed_mps()) < 0.01);
}
