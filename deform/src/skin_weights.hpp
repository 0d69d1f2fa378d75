#pragma once
// The weights of one render vertex over its chosen control points (deform/skin.hpp): the inverse-distance
// weights of Kenwright 2015 and the affine moving-least-squares weights of Schaefer et al. 2006.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "nearest_points.hpp"

namespace deform::detail {

/// Normalised inverse-distance weights (Kenwright 2015, equation 1) from the distances [m] of the vertex to
/// `count` control points; they sum to 1. A vertex on a control point takes that point alone (shared
/// equally among coincident points).
void inverseDistanceWeights(const double* distance_m, std::size_t count, double alpha, double* weight);

/// Affine moving-least-squares weights (Schaefer, McPhail & Warren 2006, section 2.1) of vertex `v_m` over
/// the control points `point_m[0 .. count)` at distances `distance_m`, with the inverse-distance weights
/// as the least-squares weight (less the one a point at `cutoff_m` would have, for the points nearer
/// than it, when cutoff_m > 0: the next nearest point's distance, so that the weights are continuous where
/// the set of nearest points changes): sum_k w_k = 1 and sum_k w_k p_k = v in every direction the points
/// span. Directions the points do not span (coplanar, collinear, fewer than four points) are dropped from the
/// fit: the weights there are those of the weighted centroid. Finite for any input; a vertex on a control
/// point takes that point alone. Returns false when the fit had to be bounded (sum |w| capped, a vertex
/// far outside nearly flat points): the weights are then not exact for affine maps.
bool movingLeastSquaresWeights(const Eigen::Vector3d& v_m, const Eigen::Vector3d* point_m,
                               const double* distance_m, std::size_t count, double alpha, double* weight,
                               double cutoff_m = 0);

/// Whether vertex `v_m` lies off the plane (or line) of the `chosen` control points by more than three
/// of their standard deviations across it: the affine fit over them then cannot reach it (the points of
/// a flat side of the hull, a vertex inside the car).
bool offsetOutOfSpan(const Eigen::Vector3d& v_m, const std::vector<Eigen::Vector3d>& control_m,
                     const std::vector<RankedPoint>& chosen);

/// While offsetOutOfSpan (at most twice: a line needs two), swaps the farthest chosen point for the
/// nearest of `candidates` (nearest first) lying off their plane by at least half the vertex's offset,
/// so the fit spans the vertex with moderate weights; a swap that leaves the points thinner is undone.
/// Returns false when the candidates held no such point (`chosen` then partly widened).
/// `thick`: widen whatever the offset, with candidates off the plane by at least the points' own extent
/// (for a vertex whose fit over thin points was bounded, movingLeastSquaresWeights).
bool widenSpan(const Eigen::Vector3d& v_m, const std::vector<Eigen::Vector3d>& control_m,
               std::vector<RankedPoint>& chosen, const std::vector<RankedPoint>& candidates,
               bool thick = false);

}  // namespace deform::detail
