#pragma once
// What a car is, fixed once it is built (the "settings" half of the settings/state split, DESIGN.md
// section 4 and Jolt's VehicleConstraintSettings): mass, wheel layout, suspension, tyres, engine,
// brakes, steering. The state that changes every step lives in Car and WheelState.
#include <deform/builtin_meshes.hpp>
#include <deform/mesh.hpp>

#include <Eigen/Core>
#include <vector>

namespace vehicle {

/// Tyre model parameters (a brush model with relaxation lengths, see tyre_model.hpp). Stiffnesses are
/// given per newton of normal load, so the slip at which a tyre saturates does not depend on its load.
struct TyreSettings {
  /// mu: friction coefficient of tyre on road, both the peak and the sliding value (dry asphalt about 1.0,
  /// wet 0.7, snow 0.3) [-].
  double friction_coefficient = 1.0;
  /// C_kappa / F_z: slope of the longitudinal force over the slip ratio at zero slip, per newton of
  /// normal load (passenger car tyres 15-25) [1/unit slip]. Saturates at slip 3 mu / 20 = 0.15.
  double longitudinal_stiffness_per_load = 20.0;
  /// C_alpha / F_z: cornering stiffness per newton of normal load (passenger cars 15-20, i.e. about
  /// 1200 N/deg at 3.7 kN) [1/rad]. Saturates at a slip angle of atan(3 mu / 18) = 9.5 deg.
  double cornering_stiffness_per_load = 18.0;
  /// sigma_x: rolling distance over which longitudinal slip builds up (Pacejka 2006, section 7.2) [m].
  double longitudinal_relaxation_m = 0.3;
  /// sigma_y: rolling distance over which the slip angle builds up (about 1.5 tyre radii) [m].
  double lateral_relaxation_m = 0.5;
  /// Damping of the standing tyre's deflection as a fraction of critical for the mass the tyre carries
  /// (Bernard and Clover 1995, low-speed tyre damping): what stops a parked car from swaying [-].
  double low_speed_damping_ratio = 1.0;
  /// Speed of the contact point above which that damping has faded out linearly [m/s].
  double low_speed_blend_mps = 2.0;
  /// C_rr: rolling resistance force over normal load (car tyre on asphalt 0.010-0.015) [-].
  double rolling_resistance = 0.012;
};

/// One wheel: where it is, its suspension and its brake. Vehicle frame (ISO 8855: X forward, Y left,
/// Z up), in the coordinates of the vehicle mesh.
struct WheelSettings {
  /// Hub centre with the car at rest and level on flat ground (design ride height) [m]. The suspension
  /// mount is placed so that the car settles with its wheels exactly here.
  Eigen::Vector3d centre_m{0, 0, 0};
  double radius_m = 0.32;         ///< tyre outer radius [m]
  double width_m = 0.22;          ///< tyre width [m] (for drawing)
  double inertia_kg_m2 = 1.2;     ///< spin inertia of wheel, tyre and its share of the driveline [kg m^2]
  bool steered = false;           ///< turns with the steering input
  bool driven = false;            ///< receives engine torque (split evenly over the driven wheels)
  bool handbrake = false;         ///< locked by the handbrake
  double brake_torque_Nm = 2500;  ///< brake torque at full brake input [N m]
  /// Spring rate at the wheel [N/m]. 35 kN/m on a 375 kg corner: 1.5 Hz ride, 0.105 m static compression.
  double spring_N_per_m = 35000;
  /// Damper rate at the wheel [N s/m]: about 0.55 of critical for a 375 kg corner.
  double damper_N_s_per_m = 4000;
  /// Suspension length from its mount to the hub at full extension (no load) [m].
  double suspension_length_m = 0.30;
  /// Compression from full extension at which the bump stop engages (10x the spring rate) [m].
  double max_compression_m = 0.22;
};

/// Everything about a car that does not change while it drives. Defaults: a 1500 kg rear-wheel-drive
/// sedan, 100 kW.
struct VehicleSettings {
  double mass_kg = 1500;  ///< whole vehicle (the chassis body carries all of it; wheels are forces) [kg]
  /// Added to the centroid of the solid hull (uniform density) to place the centre of mass [m].
  Eigen::Vector3d centre_of_mass_offset_m{0, 0, 0};
  /// Control points of the chassis collision hull when it is built from a mesh (4 .. 100,000) [-].
  std::size_t collision_points = 64;
  /// Size of the box chassis used when a car is made without a mesh [m] (wheels then from its bounding
  /// box: its bottom rides half a wheel radius above the ground).
  Eigen::Vector3d box_size_m{4.6, 1.8, 1.3};
  /// The wheels. Empty: taken from the model's wheels, or from its bounding box when it has none
  /// (wheelsFromModel).
  std::vector<WheelSettings> wheels;
  TyreSettings tyre;

  double max_steer_rad = 0.61;    ///< steering angle of the front axle at full lock (35 deg) [rad]
  double steer_rate_rad_s = 1.5;  ///< fastest change of the steering angle (lock to centre in 0.4 s) [rad/s]
  /// Share of Ackermann geometry: 0 parallel steering, 1 the inner wheel turns about the rear axle's
  /// centre of turn (tan(delta_i) = L / (R - t/2)) [-].
  double ackermann = 1.0;

  double engine_torque_Nm = 250;  ///< peak engine torque [N m]
  /// Overall ratio engine to wheels (one fixed gear: an ideal continuously variable transmission, the
  /// engine held at its power peak once torque would exceed max_power_W / wheel speed) [-].
  double gear_ratio = 8.0;
  double max_power_W = 100e3;         ///< engine power at the wheels [W]
  double handbrake_torque_Nm = 3000;  ///< brake torque on handbrake wheels at full handbrake [N m]

  double drag_area_m2 = 0.66;        ///< C_d A: drag coefficient times frontal area (0.30 x 2.2 m^2) [m^2]
  double air_density_kg_m3 = 1.225;  ///< [kg/m^3]
  double body_friction = 0.5;        ///< friction of the body shell sliding on obstacles (ODE contact mu) [-]
};

/// Four wheels for the given parts (a model's wheels). Front (steered) wheels get 55 % of the brake
/// torque, rear (driven, handbrake) wheels 45 %; sizes taken from the parts.
std::vector<WheelSettings> wheelsFromParts(const std::vector<deform::WheelPart>& parts);

/// Four wheels placed in a vehicle's bounding box when it has no wheels: axles at +-29 % of the length
/// from the middle (wheelbase 58 % of the length), track 85 % of the width, radius min(0.32 m, 22 % of
/// the height), hub half a radius below the bottom of the box (a body without wheels).
std::vector<WheelSettings> wheelsFromBoundingBox(const deform::Aabb& box);

/// settings.wheels when given, else wheelsFromParts(model.wheels), else wheelsFromBoundingBox.
std::vector<WheelSettings> wheelsFromModel(const VehicleSettings& settings,
                                           const deform::VehicleModel& model);

/// `settings` for a vehicle of `mass_kg` instead: springs, dampers, brake, handbrake and engine torques,
/// power, drag area and wheel inertias scaled by the mass ratio, so ride frequency, damping ratio, static
/// compression and accelerations stay those of the original (for the 1 kg .. 40 t stress range). Wheels
/// given in `settings` are scaled; wheels taken later from a model get the default 1500 kg values, so
/// give them here (wheelsFromModel) before scaling.
VehicleSettings settingsForMass(const VehicleSettings& settings, double mass_kg);

/// Refuses settings that cannot drive: a non-finite or non-positive mass, radius, inertia, spring,
/// relaxation length or rate, negative damping or torques, fewer than three wheels. Throws
/// deform::InputError whose message starts with `source` and names the field.
void checkVehicleSettings(const VehicleSettings& settings, const char* source = "vehicle");

}  // namespace vehicle
