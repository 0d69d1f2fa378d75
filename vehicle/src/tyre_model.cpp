// Brush tyre, suspension and steering (see tyre_model.hpp for the formulas and their sources).
#include <vehicle/tyre_model.hpp>

#include <algorithm>
#include <cmath>

namespace vehicle {
namespace {

constexpr double kBumpStopFactor = 10.0;

/// Force over linear force of the brush model at normalised slip s = |phi| / (3 mu F_z):
/// 1 - s + s^2/3 while the patch still sticks somewhere, 1 / (3 s) once it slides entirely.
double brushFactor(double s) {
  return s < 1.0 ? 1.0 - s + s * s / 3.0 : 1.0 / (3.0 * s);
}

double signOf(double x) {
  return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0);
}

}  // namespace

TyreForce brushTyreForce(double slip_ratio, double slip_angle_rad, double normal_load_N, double mu,
                         double longitudinal_stiffness_N, double cornering_stiffness_N_per_rad) {
  TyreForce out;
  if (!(normal_load_N > 0) || !(mu > 0)) return out;
  const double phi_x = longitudinal_stiffness_N * slip_ratio;
  const double phi_y = cornering_stiffness_N_per_rad * std::tan(std::clamp(slip_angle_rad, -1.5, 1.5));
  const double s = std::hypot(phi_x, phi_y) / (3.0 * mu * normal_load_N);
  const double factor = brushFactor(s);
  out.longitudinal_N = factor * phi_x;
  out.lateral_N = -factor * phi_y;
  out.sliding = s >= 1.0;
  return out;
}

TyreForce tyreForce(double slip_ratio, double slip_angle_rad, double normal_load_N,
                    const TyreSettings& tyre) {
  return brushTyreForce(slip_ratio, slip_angle_rad, normal_load_N, tyre.friction_coefficient,
                        tyre.longitudinal_stiffness_per_load * normal_load_N,
                        tyre.cornering_stiffness_per_load * normal_load_N);
}

double suspensionForce(double compression_m, double compression_rate_mps, const WheelSettings& wheel) {
  if (!(compression_m > 0)) return 0;
  double force = wheel.spring_N_per_m * compression_m + wheel.damper_N_s_per_m * compression_rate_mps;
  const double past_stop = compression_m - wheel.max_compression_m;
  if (past_stop > 0) force += kBumpStopFactor * wheel.spring_N_per_m * past_stop;
  return std::max(0.0, force);
}

double rateLimited(double current, double target, double max_rate, double dt_s) {
  const double step = max_rate * dt_s;
  return current + std::clamp(target - current, -step, step);
}

std::array<double, 2> ackermannAngles(double delta_rad, double wheelbase_m, double track_m,
                                      double ackermann) {
  if (delta_rad == 0 || !(wheelbase_m > 0)) return {delta_rad, delta_rad};
  // Turning centre on the rear axle line at distance R (signed: + to the left) from the centreline.
  const double radius_m = wheelbase_m / std::tan(delta_rad);
  const double left = std::atan(wheelbase_m / (radius_m - 0.5 * track_m));
  const double right = std::atan(wheelbase_m / (radius_m + 0.5 * track_m));
  const double a = std::clamp(ackermann, 0.0, 1.0);
  return {a * left + (1 - a) * delta_rad, a * right + (1 - a) * delta_rad};
}

TyreStepResult stepTyre(TyreState& state, const TyreStepInput& in, const TyreSettings& tyre) {
  TyreStepResult out;
  const double dt = in.dt_s, r = in.radius_m, inertia = in.inertia_kg_m2;
  const double load = std::max(0.0, in.normal_load_N);
  const double vx = in.longitudinal_speed_mps, vy = in.lateral_speed_mps;
  const double mu = tyre.friction_coefficient;
  // Friction torque that opposes spin: brakes plus rolling resistance (C_rr F_z r).
  const double resist_Nm = std::max(0.0, in.brake_torque_Nm) + tyre.rolling_resistance * load * r;

  // Wheel spin under torques T and a tyre force F(Omega1) = F0 + G Omega1, implicit Euler:
  //   I (Omega1 - Omega0) = dt (T + T_brake - r F(Omega1)),
  // with T_brake the Coulomb brake: whatever holds the wheel still if that is within resist_Nm, else
  // resist_Nm against the motion.
  auto solveSpin = [&](double f0, double g) {
    const double hold_Nm = -inertia * state.spin_rad_s / dt - in.drive_torque_Nm + r * f0;
    if (std::abs(hold_Nm) <= resist_Nm) {
      out.locked = true;
      return 0.0;
    }
    out.locked = false;
    const double brake_Nm = resist_Nm * signOf(hold_Nm);
    return (inertia * state.spin_rad_s + dt * (in.drive_torque_Nm + brake_Nm - r * f0)) /
           (inertia + dt * r * g);
  };

  if (!(load > 0) || !(mu > 0)) {  // in the air: the tread relaxes, the wheel spins freely
    state.longitudinal_deflection_m = 0;
    state.lateral_deflection_m = 0;
    state.spin_rad_s = solveSpin(0.0, 0.0);
    return out;
  }

  const double sigma_x = tyre.longitudinal_relaxation_m, sigma_y = tyre.lateral_relaxation_m;
  const double c_kappa = tyre.longitudinal_stiffness_per_load * load;  // [N per unit slip]
  const double c_alpha = tyre.cornering_stiffness_per_load * load;     // [N/rad]
  const double k_x = c_kappa / sigma_x, k_y = c_alpha / sigma_y;       // standing tread stiffness [N/m]
  const double corner_mass_kg = load / kGravity_mps2;
  const double blend = std::max(0.0, 1.0 - std::abs(vx) / tyre.low_speed_blend_mps);
  const double d_x = 2.0 * tyre.low_speed_damping_ratio * std::sqrt(k_x * corner_mass_kg) * blend;
  const double d_y = 2.0 * tyre.low_speed_damping_ratio * std::sqrt(k_y * corner_mass_kg) * blend;

  // Lateral deflection, implicit: v1 = (v0 + dt V_y) / (1 + dt |V_x| / sigma_y).
  double v1 = (state.lateral_deflection_m + dt * vy) / (1.0 + dt * std::abs(vx) / sigma_y);
  // Longitudinal deflection, implicit and linear in the new spin: u1 = a + b Omega1.
  const double denom = 1.0 + dt * std::abs(vx) / sigma_x;
  const double a = (state.longitudinal_deflection_m - dt * vx) / denom;
  const double b = dt * r / denom;

  // The brush force is the linear force times brushFactor(s); iterate on that secant factor so the
  // spin sees the saturating force while staying implicit.
  double factor = 1.0, spin = state.spin_rad_s, u1 = a;
  auto slipOf = [&](double u) {
    return std::hypot(c_kappa * u / sigma_x, c_alpha * v1 / sigma_y) / (3.0 * mu * load);
  };
  for (int iteration = 0; iteration < 8; ++iteration) {
    spin = solveSpin(k_x * factor * a - d_x * vx, k_x * factor * b + d_x * r);
    u1 = a + b * spin;
    const double next = brushFactor(slipOf(u1));
    if (std::abs(next - factor) <= 1e-9 * factor) break;
    factor = next;
  }
  double fx = factor * c_kappa * u1 / sigma_x + d_x * (spin * r - vx);
  double fy = -factor * c_alpha * v1 / sigma_y - d_y * vy;
  const double limit = mu * load, total = std::hypot(fx, fy);
  if (total > limit) {
    // Sliding (with the low-speed damper too): the force is mu F_z along the sticking force's
    // direction, a constant, so the spin follows exactly from the torques.
    fx *= limit / total;
    fy *= limit / total;
    const double slip_before = spin * r - vx;
    double sliding_spin = solveSpin(fx, 0.0);
    // The wheel caught up with the road within the step: it sticks at rolling speed instead.
    if (!out.locked && slip_before * (sliding_spin * r - vx) < 0) sliding_spin = vx / r;
    spin = sliding_spin;
    u1 = a + b * spin;
  }
  const double s = slipOf(u1);
  // A sliding tread does not wind up further: hold the deflection at the edge of sliding.
  if (s > 1.0) {
    u1 /= s;
    v1 /= s;
  }
  state.spin_rad_s = spin;
  state.longitudinal_deflection_m = u1;
  state.lateral_deflection_m = v1;
  out.force = {fx, fy, s >= 1.0 || total > limit};
  out.slip_ratio = u1 / sigma_x;
  out.slip_angle_rad = std::atan(v1 / sigma_y);
  return out;
}

}  // namespace vehicle
