#include <scenes/drive_script.hpp>

#include <algorithm>

namespace scenes {

vehicle::DriverInput DrivePlayer::inputs(double t_s, double speed_mps, double dt_s) {
  vehicle::DriverInput input;
  const std::vector<DriveKey>& keys = script_.keys;
  // The last key at or before t_s.
  const auto after = std::upper_bound(keys.begin(), keys.end(), t_s,
                                      [](double t, const DriveKey& key) { return t < key.t_s; });
  if (after == keys.begin()) return input;
  const DriveKey& key = *(after - 1);
  double throttle = key.throttle, brake = key.brake, steering = key.steering;
  if (after != keys.end() && after->t_s > key.t_s) {
    const double s = (t_s - key.t_s) / (after->t_s - key.t_s);
    throttle += s * (after->throttle - key.throttle);
    brake += s * (after->brake - key.brake);
    steering += s * (after->steering - key.steering);
  }
  if (key.target_speed_kmh) {
    input = controller_.update(*key.target_speed_kmh / 3.6, speed_mps, dt_s);
  } else {
    controller_.reset();
    input.throttle = throttle;
    input.brake = brake;
  }
  input.steering = steering;
  input.handbrake = key.handbrake;
  return input;
}

}  // namespace scenes
