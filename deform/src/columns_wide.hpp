#pragma once
// The crush columns' sweep (anchored columns: each holds its point at its rest place, which moves with
// the core) four columns at a time where AVX2 runs. The columns of a sweep touch distinct points, so four
// side by side, each lane with the one-at-a-time operations in their order, and the reaction summed lane by
// lane in the sweep's order, give the same bits (the test `the wide sweep...`). A lane whose multiplier is
// not surely within its limit (columnSurelyWithinLimit) takes the one-at-a-time limit.
#include <deform/constraints.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace deform {

/// What the column sweep reads and writes.
struct ColumnSweep {
  Eigen::Vector3d* x = nullptr;  ///< positions [m]
  const double* w = nullptr;     ///< inverse masses [1/kg]
  const double* mass_kg = nullptr;
  const uint32_t* order = nullptr;  ///< the columns in sweep order (BodySettings::column_order)
  const SpokeConstraint* spokes = nullptr;
  bool points_in_order = false;  ///< spokes[k].point == k for every k: four in a row are read as rows
  const Eigen::Vector3d* rest_m = nullptr;  ///< each column's rest place, in the body's frame [m]
  Eigen::Vector3d shift_m{0, 0, 0};         ///< the core's displacement: rest places move with it [m]
  Eigen::Vector3d core_m{0, 0, 0};          ///< the core's rest place (the twist's origin) [m]
  const DistanceFactors* factors = nullptr;
  Eigen::Vector3d* lambda = nullptr;  ///< multipliers [N s^2]
  // The force limit (kLimited).
  const Eigen::Vector3d* normals = nullptr;
  const YieldLimits* limits = nullptr;
  const double* taken_m = nullptr;    ///< what hardening has added to each yield [m]
  const uint8_t* bottomed = nullptr;  ///< crushed to its clamp: rigid inward
  double h2 = 0;                      ///< substep length squared [s^2]
};

/// The reaction of the columns' corrections on the core: their summed momentum x h and its moment.
struct ColumnReaction {
  Eigen::Vector3d pull{0, 0, 0}, twist{0, 0, 0};
};

/// What the spokes' sweep reads and writes (spokes: distance constraints from each point to its anchor on
/// the core, the non-anchored columns).
struct SpokeSweep {
  Eigen::Vector3d* x = nullptr;  ///< positions [m]
  const double* w = nullptr;     ///< inverse masses [1/kg]
  const double* mass_kg = nullptr;
  const uint32_t* order = nullptr;  ///< the spokes in sweep order (BodySettings::column_order)
  const SpokeConstraint* spokes = nullptr;
  const Eigen::Vector3d* anchors_m = nullptr;  ///< each spoke's anchor relative to the core [m]
  Eigen::Vector3d core_m{0, 0, 0};             ///< the core's place now [m]
  const double* rest_m = nullptr;              ///< rest lengths [m]
  const DistanceFactors* factors = nullptr;
  double* lambda = nullptr;           ///< multipliers [N s^2]
  const YieldForce* yield = nullptr;  ///< yield forces (kLimited)
  double h2 = 0;                      ///< substep length squared [s^2]
};

/// Projects the spokes order[begin .. end) in order (projectDistance to a copy of the anchor, which the
/// core's summed reaction moves after the sweep), adding their reaction to `out`; `wide`: four at a time
/// where the machine can (their points are distinct).
template <bool kLimited>
void sweepSpokes(const SpokeSweep& s, std::size_t begin, std::size_t end, bool wide, ColumnReaction& out);

/// The columns k of [begin, end) not surely elastic (columnSurelyElastic false for the elastic displacement
/// x - shift - rest), in order, appended to `which`; `wide`: four at a time where the machine can.
void columnsNotSurelyElastic(const Eigen::Vector3d* x, const SpokeConstraint* spokes,
                             const Eigen::Vector3d* rest_m, const Eigen::Vector3d* normals,
                             const YieldLimits* limits, const Eigen::Vector3d& shift_m, std::size_t begin,
                             std::size_t end, bool wide, std::vector<uint32_t>& which);

/// Projects the columns order[begin .. end) in order, adding their reaction to `out`; `wide`: four at a
/// time where the machine can.
template <bool kLimited>
void sweepColumns(const ColumnSweep& s, std::size_t begin, std::size_t end, bool wide, ColumnReaction& out);

}  // namespace deform
