#pragma once
// The order in which a Gauss-Seidel sweep visits the pair constraints (edges, bends): the body's two
// halves, each free of the other's points so that two threads can sweep them side by side, then the
// constraints across the cut; and within each part, windows of consecutive constraints whose members
// share no point where they can, so that a sweep is not one long chain of dependent updates.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace deform {

/// Constraints per window (at most 64: a window's greedy colouring needs no more colours than that).
inline constexpr std::size_t kSweepWindow = 32;

/// The points' indices in order along the longest side of their bounding box, ties by index.
std::vector<uint32_t> orderAlongLongestSide(const std::vector<Eigen::Vector3d>& points_m);

/// Which half of the body each point lies in (0 or 1): split at the median of the points' coordinate
/// along the longest side of their bounding box, ties broken by index, so the halves hold n / 2 and
/// n - n / 2 points and meet across one cross-section.
std::vector<uint8_t> bodyHalves(const std::vector<Eigen::Vector3d>& points_m);

/// A sweep order of pair constraints: `order` is a permutation of them; order[0 .. half_end[0]) have both
/// points in half 0, order[half_end[0] .. half_end[1]) both in half 1, and the rest cross the cut.
struct SweepOrder {
  std::vector<uint32_t> order;
  std::array<uint32_t, 2> half_end{};
};

/// Each part in input order from window to window (`window` consecutive pairs of the part), and within a
/// window by a greedy colouring (first fit, in input order), so that consecutive pairs of one colour share
/// no point. Deterministic.
///
/// `by_level`: then each part is re-sorted, stably, by dependency level (a pair's level is one more than
/// the highest level of the pairs before it that share a point). Every pair keeps its place among the pairs
/// sharing a point with it, so a Gauss-Seidel sweep gives the same positions to the bit; but the pairs of a
/// level share no point, so the sweep's fours and eights are not only disjoint but independent of the ones
/// just before them (a 4,000-point sedan's edges fall into 41 levels of 4 to 628), and do not wait for
/// their stores.
SweepOrder sweepOrder(const std::vector<std::array<uint32_t, 2>>& pairs, const std::vector<uint8_t>& halves,
                      std::size_t window = kSweepWindow, bool by_level = true);

}  // namespace deform
