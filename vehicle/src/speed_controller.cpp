// PI speed control with conditional integration (anti-windup).
#include <vehicle/driver_input.hpp>

#include <algorithm>

namespace vehicle {

DriverInput SpeedController::update(double target_mps, double speed_mps, double dt_s) {
  DriverInput input;
  const double target = std::max(0.0, target_mps);
  if (target < settings_.hold_below_mps && speed_mps < settings_.hold_below_mps) {
    integral_m_ = 0;
    input.brake = 1;
    return input;
  }
  const double error = target - speed_mps;
  const double command = settings_.throttle_per_mps * error + settings_.throttle_per_m * integral_m_;
  // Integrate only while the throttle is not pinned in the direction the error pushes it.
  const bool saturated = (command >= 1 && error > 0) || (command <= 0 && error < 0);
  if (!saturated) integral_m_ += error * dt_s;
  integral_m_ = std::max(0.0, integral_m_);
  input.throttle = std::clamp(command, 0.0, 1.0);
  if (-error > settings_.brake_dead_band_mps) {
    input.throttle = 0;
    input.brake = std::clamp(settings_.brake_per_mps * (-error - settings_.brake_dead_band_mps), 0.0, 1.0);
  }
  return input;
}

}  // namespace vehicle
