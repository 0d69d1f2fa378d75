#pragma once
// Distance constraints (edges, bends) swept four at a time where four neighbours in the sweep share no
// point, eight (two fours, loaded before either is stored) where eight do, and thirty-two in stages where
// thirty-two do (each stage over all of them before the next: their square roots and divisions overlap).
// Such projections commute, so projecting them side by side, each in its own SIMD lane with the operations
// of projectDistance in the same order (no fused multiply-add), gives the one-by-one Gauss-Seidel sweep's
// result to the bit (the test `the wide sweep...`). AVX2, chosen at run time; the scalar sweep elsewhere.
#include <deform/constraints.hpp>
#include <deform/solver_params.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace deform {

/// One kind of pair constraint in sweep order, as the sweep reads it.
struct DistanceSweep {
  Eigen::Vector3d* x = nullptr;       ///< positions [m]
  const double* w = nullptr;          ///< inverse masses [1/kg]
  const uint32_t* pairs = nullptr;    ///< the two points of constraint k at 2 k, 2 k + 1
  const uint8_t* disjoint = nullptr;  ///< disjointRuns: how many from k on share no point
  const double* rest_m = nullptr;     ///< rest lengths [m]
  const DistanceFactors* factors = nullptr;
  double* lambda = nullptr;           ///< multipliers [N s^2]
  const YieldForce* yield = nullptr;  ///< yield forces (the force-limited sweep)
  double h2 = 0;                      ///< substep length squared [s^2]
};

/// The two points of each pair, interleaved (DistanceSweep::pairs).
template <class Constraint, class First, class Second>
std::vector<uint32_t> interleavedPairs(const std::vector<Constraint>& constraints, First first,
                                       Second second) {
  std::vector<uint32_t> pairs;
  pairs.reserve(2 * constraints.size());
  for (const Constraint& c : constraints) {
    pairs.push_back(first(c));
    pairs.push_back(second(c));
  }
  return pairs;
}

/// The longest run disjointRuns reports.
inline constexpr std::size_t kLongestRun = 255;

/// For each constraint k, how many constraints from k on (k included, at most kLongestRun) share no point
/// with each other: 0 where constraint k joins a point to itself.
std::vector<uint8_t> disjointRuns(const std::vector<uint32_t>& pairs);

/// Constraints of [begin, end) whose squared length |x_a - x_b|^2 is outside their elastic band
/// (ElasticBand::holds false), in order, with that squared length (the same bits as Eigen's
/// squaredNorm): appended to `which` and `length_m2`. `wide`: four at a time where AVX2 runs.
void outsideBands(const Eigen::Vector3d* x, const uint32_t* pairs, const ElasticBand* bands,
                  std::size_t begin, std::size_t end, bool wide, std::vector<uint32_t>& which,
                  std::vector<double>& length_m2);

/// Projects constraints [begin, end) in order (projectDistance, force-limited by `yield` when
/// kLimited): eight or four side by side wherever disjoint, one at a time elsewhere; `wide` false: one
/// at a time.
template <bool kLimited>
void sweepDistances(const DistanceSweep& sweep, std::size_t begin, std::size_t end, bool wide);

}  // namespace deform
