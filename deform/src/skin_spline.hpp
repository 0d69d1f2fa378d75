#pragma once
// The spline skin's weights (deform/skin.hpp, SkinMethod::spline): the polyharmonic spline phi(r) = r^3
// with a linear polynomial through every control point, written as weights on the control points'
// displacements.
#include <Eigen/Core>
#include <vector>

namespace deform::detail {

/// The interpolating spline s(x) = sum_i a_i |x - c_i|^3 + b_0 + b^T x with sum_i a_i = 0 and
/// sum_i a_i c_i = 0 (Duchon 1977; the cubic case of the polyharmonic splines, e.g. Wendland 2005,
/// "Scattered Data Approximation", section 8.3). It interpolates the control points' displacements,
/// reproduces any affine map exactly, and is twice continuously differentiable everywhere: no crease
/// where a vertex's nearest points change, because every vertex uses every point. For the values u_i the
/// coefficients solve [A P; P^T 0] [a; b] = [u; 0] with A_ij = |c_i - c_j|^3 and P_i = (1, c_i), so
/// s(v) = w(v)^T u with w(v) the first N entries of [A P; P^T 0]^-1 [phi(v); 1; v]: weights that sum to
/// one and whose first moment is v.
class SplineWeights {
 public:
  /// Factors the system once. Throws InputError when the points do not span three dimensions (then
  /// the linear part is not determined).
  explicit SplineWeights(const std::vector<Eigen::Vector3d>& control_m);

  /// The weights of the vertex at `v_m`, one per control point in index order.
  void weigh(const Eigen::Vector3d& v_m, double* weight) const;

 private:
  std::vector<Eigen::Vector3d> control_;  ///< the points, centred and scaled (conditioning)
  Eigen::Vector3d centre_m_;
  double scale_per_m_ = 1;
  Eigen::MatrixXd inverse_rows_;  ///< the first N rows of the inverse system matrix, N x (N + 4)
};

}  // namespace deform::detail
