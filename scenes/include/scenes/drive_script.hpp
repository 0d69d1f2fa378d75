#pragma once
// A car's drive script played over time: keys of throttle, brake and steering (linear between keys),
// handbrake and speed control (held from a key to the next). Before the first key: no input.
#include <scenes/scene.hpp>

#include <vehicle/driver_input.hpp>

namespace scenes {

class DrivePlayer {
 public:
  explicit DrivePlayer(DriveScript script) : script_(std::move(script)) {}

  /// Inputs at time t_s for a car going at forward speed speed_mps, after a step of dt_s (the speed
  /// controller integrates over it).
  vehicle::DriverInput inputs(double t_s, double speed_mps, double dt_s);
  /// The speed controller: the player's only state (the script is fixed), for saving a run.
  const vehicle::SpeedController& controller() const { return controller_; }
  vehicle::SpeedController& controller() { return controller_; }

 private:
  DriveScript script_;
  vehicle::SpeedController controller_;
};

}  // namespace scenes
