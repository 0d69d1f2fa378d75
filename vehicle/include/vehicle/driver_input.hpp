#pragma once
// What a driver (or a scene script) does to a car each step, and a speed controller that turns a
// target speed into pedal positions.
#include <optional>

namespace vehicle {

struct DriverInput {
  double throttle = 0;  ///< accelerator pedal, 0 .. 1 (clamped) [-]
  double brake = 0;     ///< brake pedal, 0 .. 1 (clamped) [-]
  double steering = 0;  ///< steering wheel, -1 (full right) .. 1 (full left), times max_steer_rad [-]
  /// Target steering angle of the front axle (bicycle-model angle, + left) [rad]; overrides `steering`
  /// when set; clamped to +-max_steer_rad.
  std::optional<double> steer_angle_rad;
  bool handbrake = false;  ///< locks the handbrake wheels with handbrake_torque_Nm
  bool reverse = false;    ///< reverse gear: throttle drives backwards
};

struct SpeedControllerSettings {
  double throttle_per_mps = 0.5;     ///< proportional gain on the speed error [1/(m/s)]
  double throttle_per_m = 0.1;       ///< integral gain on the accumulated error [1/m]
  double brake_per_mps = 0.3;        ///< brake pedal per m/s of overspeed beyond the dead band [1/(m/s)]
  double brake_dead_band_mps = 0.5;  ///< overspeed tolerated before braking [m/s]
  double hold_below_mps = 0.3;       ///< target and speed both below this: hold the car (full brake) [m/s]
};

/// A PI speed controller with anti-windup: throttle for underspeed, brake for overspeed, full brake to
/// hold the car when asked to stop. Forward driving only (a negative target counts as zero).
class SpeedController {
 public:
  explicit SpeedController(const SpeedControllerSettings& settings = {}) : settings_(settings) {}
  /// Pedals for driving at `target_mps` when the car's forward speed is `speed_mps`, after a step of
  /// `dt_s`. Steering and handbrake of the result are left at rest; copy them from elsewhere.
  DriverInput update(double target_mps, double speed_mps, double dt_s);
  void reset() { integral_m_ = 0; }
  /// The accumulated speed error: the controller's whole state, for saving and restoring a run [m].
  double integral_m() const { return integral_m_; }
  void setIntegral_m(double integral_m) { integral_m_ = integral_m; }

 private:
  SpeedControllerSettings settings_;
  double integral_m_ = 0;  ///< accumulated speed error [m]
};

}  // namespace vehicle
