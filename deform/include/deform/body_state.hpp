#pragma once
// The small per-car part of a deformable body (DESIGN.md section 4): everything a step changes. A
// snapshot can be saved, restored bit-exactly and hashed (determinism checks, replays).
#include <deform/body_settings.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace deform {

/// Everything a step changes: the control points' positions and velocities, the rest lengths and places
/// plasticity moved, the plastic work, the clock and the sleep state.
struct BodyState {
  std::vector<Eigen::Vector3d> positions_m;     ///< control points, vehicle frame [m]
  std::vector<Eigen::Vector3d> velocities_mps;  ///< relative to the chassis, from positions [m/s]
  std::vector<double> edge_rest_m;              ///< current rest lengths (plasticity moves them) [m]
  std::vector<double> spoke_rest_m;             ///< [m]
  /// Where each crush column holds its point now (plastic flow moves it), vehicle frame [m].
  std::vector<Eigen::Vector3d> column_rest_m;
  std::vector<double> bend_rest_m;  ///< [m]
  double plastic_work_J = 0;        ///< work done by plastic flow since the start [J]
  double time_s = 0;                ///< simulated time [s]
  double sleep_timer_s = 0;         ///< how long the body has been slow and free of contact [s]
  bool sleeping = false;            ///< steps do no work
  /// Inertial load when the body fell asleep: specific force [m/s^2], angular velocity [rad/s],
  /// angular acceleration [rad/s^2] (scaled); a change wakes the body.
  Eigen::Vector3d sleep_load_mps2{0, 0, 0}, sleep_angular_velocity_radps{0, 0, 0},
      sleep_angular_acceleration_radps2{0, 0, 0};
};

/// The undeformed body at rest.
BodyState restState(const BodySettings& settings);

/// 64-bit FNV-1a over every field's bytes: equal states give equal hashes on one platform.
uint64_t hashState(const BodyState& state);

/// Bit-exact binary snapshot of the state.
std::vector<uint8_t> saveState(const BodyState& state);

/// The state saved by saveState. Throws InputError when the bytes are not a snapshot or do not match
/// `settings` (point or constraint counts).
BodyState restoreState(const BodySettings& settings, std::span<const uint8_t> bytes);

}  // namespace deform
