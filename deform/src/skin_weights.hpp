#pragma once
// The weights of one render vertex over its chosen control points (deform/skin.hpp): the inverse-distance
// weights of Kenwright 2015 and the affine moving-least-squares weights of Schaefer et al. 2006.
#include <Eigen/Core>
#include <cstddef>

namespace deform::detail {

/// Normalised inverse-distance weights (Kenwright 2015, equation 1) from the distances [m] of the vertex to
/// `count` control points; they sum to 1. A vertex on a control point takes that point alone (shared
/// equally among coincident points).
void inverseDistanceWeights(const double* distance_m, std::size_t count, double alpha, double* weight);

/// Affine moving-least-squares weights (Schaefer, McPhail & Warren 2006, section 2.1) of vertex `v_m` over
/// the control points `point_m[0 .. count)` at distances `distance_m`, with the inverse-distance weights
/// as the least-squares weight: sum_k w_k = 1 and sum_k w_k p_k = v in every direction the points span.
/// Directions the points do not span (coplanar, collinear, fewer than four points) are dropped from the
/// fit: the weights there are those of the weighted centroid. Finite for any input; a vertex on a control
/// point takes that point alone.
void movingLeastSquaresWeights(const Eigen::Vector3d& v_m, const Eigen::Vector3d* point_m,
                               const double* distance_m, std::size_t count, double alpha, double* weight);

}  // namespace deform::detail
