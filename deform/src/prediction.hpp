#pragma once
// The substep's prediction over a range of control points (DeformableBody::beginSubstep): exact viscous
// decay of the motion relative to the core, the explicit velocity update with the inertial forces, then
// the positions. One point at a time, or four side by side (AVX2, chosen at run time), each lane with
// the one-at-a-time operations in their order and the sums added lane by lane in point order: the same
// bits either way (the test `the wide sweep...`).
#include <Eigen/Core>
#include <cstddef>

namespace deform {

/// What the prediction reads and writes.
struct Prediction {
  Eigen::Vector3d* x = nullptr;             ///< positions [m], moved by the prediction
  Eigen::Vector3d* previous = nullptr;      ///< where each point began the substep [m] (written)
  const Eigen::Vector3d* v = nullptr;       ///< velocities at the substep's start [m/s]
  const double* mass_kg = nullptr;          ///< point masses
  const double* max_deviation_m = nullptr;  ///< visual-constraint radii: travel is capped at twice it
  Eigen::Vector3d core_m{0, 0, 0};          ///< the core's place [m]
  Eigen::Vector3d core_velocity_mps{0, 0, 0};
  Eigen::Vector3d load_mps2{0, 0, 0}, omega_radps{0, 0, 0}, alpha_radps2{0, 0, 0};
  double h_s = 0, decay = 1, inertial_scale = 0;
  bool inertial = false;  ///< whether the inertial forces act (any load, rotation or angular acceleration)
};

/// The prediction's sums over its points.
struct PredictionSums {
  double damping_loss_J = 0, inertial_work_J = 0;
  Eigen::Vector3d to_core_Ns{0, 0, 0};  ///< the drag's reaction on the core [N s]
};

/// Predicts points [begin, end) in order, adding to `sums`; `wide`: four at a time where AVX2 runs.
void predictPoints(const Prediction& p, std::size_t begin, std::size_t end, bool wide, PredictionSums& sums);

}  // namespace deform
