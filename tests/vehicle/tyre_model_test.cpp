// The tyre, suspension and steering functions alone (vehicle/tyre_model.hpp).
#include <vehicle/tyre_model.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace vehicle;

namespace {

constexpr double kLoad_N = 3680;  // a quarter of a 1500 kg car

TyreStepInput rolling(double dt, double vx) {
  TyreStepInput in;
  in.dt_s = dt;
  in.normal_load_N = kLoad_N;
  in.longitudinal_speed_mps = vx;
  return in;
}

}  // namespace

TEST_CASE("brush tyre: linear at small slip, saturating at mu Fz, friction circle", "[vehicle][tyre]") {
  const TyreSettings tyre;
  const double c_kappa = tyre.longitudinal_stiffness_per_load * kLoad_N;
  const double c_alpha = tyre.cornering_stiffness_per_load * kLoad_N;
  // Slope at zero slip is the stiffness.
  CHECK(tyreForce(1e-5, 0, kLoad_N, tyre).longitudinal_N == Approx(c_kappa * 1e-5).epsilon(1e-4));
  CHECK(tyreForce(0, 1e-5, kLoad_N, tyre).lateral_N == Approx(-c_alpha * 1e-5).epsilon(1e-4));
  // Monotone up to the friction limit, flat beyond (no drop past the peak in a brush model).
  double previous = 0;
  for (double kappa = 0.01; kappa < 1.0; kappa += 0.01) {
    const double fx = tyreForce(kappa, 0, kLoad_N, tyre).longitudinal_N;
    CHECK(fx >= previous - 1e-9);
    CHECK(fx <= tyre.friction_coefficient * kLoad_N * (1 + 1e-12));
    previous = fx;
  }
  const TyreForce sliding = tyreForce(0.5, 0, kLoad_N, tyre);
  CHECK(sliding.sliding);
  CHECK(sliding.longitudinal_N == Approx(tyre.friction_coefficient * kLoad_N));
  // Opposite slips give opposite forces.
  CHECK(tyreForce(-0.05, 0, kLoad_N, tyre).longitudinal_N ==
        Approx(-tyreForce(0.05, 0, kLoad_N, tyre).longitudinal_N));
  CHECK(tyreForce(0, 0.05, kLoad_N, tyre).lateral_N < 0);
  // Combined slip stays inside the friction circle, and braking takes away cornering force.
  for (double kappa : {-0.3, -0.1, 0.0, 0.05, 0.2})
    for (double alpha : {-0.3, -0.05, 0.0, 0.1, 0.4}) {
      const TyreForce f = tyreForce(kappa, alpha, kLoad_N, tyre);
      CHECK(std::hypot(f.longitudinal_N, f.lateral_N) <= tyre.friction_coefficient * kLoad_N * (1 + 1e-12));
    }
  CHECK(std::abs(tyreForce(-0.1, 0.05, kLoad_N, tyre).lateral_N) <
        std::abs(tyreForce(0, 0.05, kLoad_N, tyre).lateral_N));
  // No load or no friction: no force.
  CHECK(tyreForce(0.1, 0.1, 0, tyre).longitudinal_N == 0);
  CHECK(brushTyreForce(0.1, 0.1, kLoad_N, 0, 1e5, 1e5).lateral_N == 0);
}

TEST_CASE("tyre relaxes to the steady slip at speed and holds still at standstill", "[vehicle][tyre]") {
  const TyreSettings tyre;
  for (double dt : {1.0 / 240, 1.0 / 2000}) {
    // A free wheel on a road moving at 20 m/s spins up to roll with it.
    TyreState state;
    TyreStepInput in = rolling(dt, 20.0);
    for (int i = 0; i < static_cast<int>(2 / dt); ++i) stepTyre(state, in, tyre);
    CHECK(state.spin_rad_s * in.radius_m == Approx(20.0).epsilon(2e-3));
    // Steady lateral slip: the deflection relaxes to sigma tan(alpha) and the force to the brush force.
    in.lateral_speed_mps = 20.0 * std::tan(0.02);
    TyreStepResult result;
    for (int i = 0; i < static_cast<int>(1 / dt); ++i) result = stepTyre(state, in, tyre);
    CHECK(result.slip_angle_rad == Approx(0.02).epsilon(1e-3));
    CHECK(result.force.lateral_N ==
          Approx(tyreForce(result.slip_ratio, 0.02, kLoad_N, tyre).lateral_N).epsilon(0.02));
  }
  // At standstill with the brake on and no motion nothing happens at all.
  TyreState parked;
  TyreStepInput still = rolling(1.0 / 500, 0.0);
  still.brake_torque_Nm = 1000;
  for (int i = 0; i < 1000; ++i) {
    const TyreStepResult r = stepTyre(parked, still, tyre);
    CHECK(r.locked);
    CHECK(r.force.longitudinal_N == 0);
    CHECK(r.force.lateral_N == 0);
  }
  // Pushed sideways at standstill the tread deflects like a damped spring, and never beyond sliding.
  TyreStepInput pushed = rolling(1.0 / 500, 0.0);
  pushed.lateral_speed_mps = 0.01;
  TyreState spring;
  const TyreStepResult first = stepTyre(spring, pushed, tyre);
  CHECK(first.force.lateral_N < 0);
  for (int i = 0; i < 5000; ++i) stepTyre(spring, pushed, tyre);
  CHECK(std::abs(stepTyre(spring, pushed, tyre).force.lateral_N) <=
        tyre.friction_coefficient * kLoad_N * (1 + 1e-9));
}

TEST_CASE("brakes lock a wheel as Coulomb friction and drive torque spins it", "[vehicle][tyre]") {
  const TyreSettings tyre;
  const double dt = 1.0 / 500;
  // Full brake at 25 m/s: the wheel locks and the tyre slides at -mu Fz.
  TyreState state;
  state.spin_rad_s = 25.0 / 0.32;
  TyreStepInput in = rolling(dt, 25.0);
  in.brake_torque_Nm = 3000;
  TyreStepResult r;
  for (int i = 0; i < 100; ++i) r = stepTyre(state, in, tyre);
  CHECK(r.locked);
  CHECK(state.spin_rad_s == 0);
  CHECK(r.force.sliding);
  CHECK(r.force.longitudinal_N == Approx(-tyre.friction_coefficient * kLoad_N));
  // A weak brake only slows the wheel: it never reverses it.
  TyreState weak;
  weak.spin_rad_s = 10;
  TyreStepInput in_air = rolling(dt, 0.0);
  in_air.normal_load_N = 0;
  in_air.brake_torque_Nm = 12;  // 10 rad/s^2 on 1.2 kg m^2
  for (int i = 0; i < 250; ++i) stepTyre(weak, in_air, tyre);
  CHECK(weak.spin_rad_s == Approx(5.0).epsilon(1e-9));
  for (int i = 0; i < 1000; ++i) stepTyre(weak, in_air, tyre);
  CHECK(weak.spin_rad_s == 0);
  // Drive torque beyond what the tyre can pass spins the wheel up; the force stays at mu Fz.
  TyreState spinning;
  TyreStepInput launch = rolling(dt, 0.0);
  launch.drive_torque_Nm = 3000;  // more than mu Fz r = 1178 N m
  for (int i = 0; i < 50; ++i) r = stepTyre(spinning, launch, tyre);
  CHECK(spinning.spin_rad_s > 10);
  CHECK(r.force.longitudinal_N == Approx(tyre.friction_coefficient * kLoad_N).epsilon(1e-6));
}

TEST_CASE("suspension pushes only, with a bump stop", "[vehicle][tyre]") {
  const WheelSettings w;
  CHECK(suspensionForce(0, 0, w) == 0);
  CHECK(suspensionForce(-0.1, 1, w) == 0);
  CHECK(suspensionForce(0.1, 0, w) == Approx(0.1 * w.spring_N_per_m));
  CHECK(suspensionForce(0.1, 0.2, w) == Approx(0.1 * w.spring_N_per_m + 0.2 * w.damper_N_s_per_m));
  CHECK(suspensionForce(0.01, -10, w) == 0);  // rebounding fast: the wheel does not pull
  CHECK(suspensionForce(w.max_compression_m + 0.01, 0, w) ==
        Approx((w.max_compression_m + 0.01) * w.spring_N_per_m + 0.01 * 10 * w.spring_N_per_m));
}

TEST_CASE("steering: rate limit and Ackermann geometry", "[vehicle][tyre]") {
  CHECK(rateLimited(0, 1, 2, 0.1) == Approx(0.2));
  CHECK(rateLimited(0, -1, 2, 0.1) == Approx(-0.2));
  CHECK(rateLimited(0.95, 1, 2, 0.1) == 1);
  const double wheelbase = 2.8, track = 1.54;
  const auto angles = ackermannAngles(0.3, wheelbase, track, 1.0);
  CHECK(angles[0] > 0.3);  // inner (left) wheel turns more in a left turn
  CHECK(angles[1] < 0.3);
  // Both wheels' axles pass through one turning centre on the rear axle line.
  const double radius = wheelbase / std::tan(0.3);
  CHECK(wheelbase / std::tan(angles[0]) == Approx(radius - 0.5 * track));
  CHECK(wheelbase / std::tan(angles[1]) == Approx(radius + 0.5 * track));
  const auto right_turn = ackermannAngles(-0.3, wheelbase, track, 1.0);
  CHECK(right_turn[0] == Approx(-angles[1]));
  CHECK(right_turn[1] == Approx(-angles[0]));
  const auto parallel = ackermannAngles(0.3, wheelbase, track, 0.0);
  CHECK(parallel[0] == 0.3);
  CHECK(parallel[1] == 0.3);
  CHECK(ackermannAngles(0, wheelbase, track, 1.0)[0] == 0);
}
