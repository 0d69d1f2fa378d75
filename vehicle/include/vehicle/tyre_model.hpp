#pragma once
// The wheel as forces (Kenwright 2015 drives its car this way; so do Bullet's btRaycastVehicle and
// Unity's WheelCollider): pure functions for the tyre, the suspension and the steering, testable alone.
//
// Tyre: the brush model with a parabolic pressure distribution and combined slip (Pacejka, "Tire and
// Vehicle Dynamics", 2nd ed. 2006, section 3.2; Fiala 1954). With linear forces phi = (C_kappa kappa,
// C_alpha tan(alpha)) and s = |phi| / (3 mu F_z):
//   |F| = mu F_z (3 s - 3 s^2 + s^3) for s < 1, |F| = mu F_z beyond (full sliding),
// along phi: the friction circle is built in and the force never drops past the peak.
//
// Low speed: slip = velocity / speed divides by zero at standstill. Instead the tyre carries a
// deflection u (longitudinal) and v (lateral) that builds up over a relaxation length sigma
// (Pacejka 2006, section 7.2; Bernard and Clover, SAE 950311, 1995):
//   du/dt = (Omega r - V_x) - |V_x| u / sigma_x,   kappa' = u / sigma_x,
//   dv/dt = V_y - |V_x| v / sigma_y,               tan(alpha') = v / sigma_y,
// so at speed kappa' and alpha' relax to the usual slips, and at standstill the deflection is a spring
// that holds a parked car where it is (no creep), with a damper that fades out by low_speed_blend_mps
// (no jitter). Wheel spin and deflection are integrated implicitly, brakes as Coulomb friction that can
// hold the wheel still, so the wheel is stable at any rate the world steps at.
#include <vehicle/vehicle_settings.hpp>

#include <array>

namespace vehicle {

/// The gravity a car's static wheel loads and a tyre's corner mass are figured with [m/s^2] (not the
/// world's gravity setting).
inline constexpr double kGravity_mps2 = 9.81;

/// Tyre force in the wheel's ground plane: x along the wheel's heading, y to its left [N].
struct TyreForce {
  double longitudinal_N = 0;  ///< + drives the car forward
  double lateral_N = 0;       ///< + pushes to the left
  bool sliding = false;       ///< the friction limit mu F_z is reached
};

/// Brush-model force for a slip ratio kappa = (Omega r - V_x) / |V_x| and a slip angle alpha
/// = atan(V_y / |V_x|) (positive when the contact patch moves to the wheel's left, so the force is
/// negative). Stiffnesses C_kappa [N per unit slip] and C_alpha [N/rad]. Zero for no load or mu <= 0.
TyreForce brushTyreForce(double slip_ratio, double slip_angle_rad, double normal_load_N, double mu,
                         double longitudinal_stiffness_N, double cornering_stiffness_N_per_rad);

/// brushTyreForce with the stiffnesses and mu of `tyre` (stiffness per load times the load).
TyreForce tyreForce(double slip_ratio, double slip_angle_rad, double normal_load_N, const TyreSettings& tyre);

/// Suspension force along the contact normal [N], >= 0 (a wheel pushes, never pulls): spring on the
/// compression from full extension plus damper on its rate, plus a bump stop of ten times the spring
/// rate past max_compression_m.
double suspensionForce(double compression_m, double compression_rate_mps, const WheelSettings& wheel);

/// `current` moved towards `target` by at most max_rate * dt.
double rateLimited(double current, double target, double max_rate, double dt_s);

/// Left and right wheel steering angles [rad] for a bicycle-model angle `delta_rad` (+ turns left):
/// Ackermann (tan(delta_inner) = L / (R - t/2), tan(delta_outer) = L / (R + t/2), R = L / tan(delta))
/// blended with parallel steering by `ackermann` in [0, 1].
std::array<double, 2> ackermannAngles(double delta_rad, double wheelbase_m, double track_m, double ackermann);

/// What changes in a tyre from step to step.
struct TyreState {
  double spin_rad_s = 0;                 ///< wheel angular velocity about its axle, + rolling forward [rad/s]
  double longitudinal_deflection_m = 0;  ///< u: tread deflection along the heading [m]
  double lateral_deflection_m = 0;       ///< v: tread deflection to the left [m]
};

/// The tyre's inputs for one step, in its contact frame.
struct TyreStepInput {
  double dt_s = 0;           ///< step [s]
  double normal_load_N = 0;  ///< F_z from the suspension; 0 when the wheel is in the air [N]
  double longitudinal_speed_mps =
      0;  ///< V_x: contact point velocity relative to the ground along the heading [m/s]
  double lateral_speed_mps = 0;  ///< V_y: the same to the wheel's left [m/s]
  double drive_torque_Nm = 0;    ///< engine torque on this wheel, + forward [N m]
  double brake_torque_Nm = 0;    ///< brake torque available (friction: can hold the wheel still) [N m]
  double radius_m = 0.32;        ///< [m]
  double inertia_kg_m2 = 1.2;    ///< [kg m^2]
};

/// One step's result: the force on the car at the contact point and the slips that produced it.
struct TyreStepResult {
  TyreForce force;
  double slip_ratio = 0;      ///< kappa' = u / sigma_x [-]
  double slip_angle_rad = 0;  ///< alpha' = atan(v / sigma_y) [rad]
  bool locked = false;        ///< the brakes (or rolling resistance) held the wheel still
};

/// Advances spin and deflections by one step (implicit in the spin and the deflections, the brake as
/// Coulomb friction, deflections held at the sliding limit) and returns the contact force.
TyreStepResult stepTyre(TyreState& state, const TyreStepInput& input, const TyreSettings& tyre);

}  // namespace vehicle
