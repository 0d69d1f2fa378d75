// The spline skin's weights (skin_spline.hpp).
#include "skin_spline.hpp"

#include <deform/error.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

namespace deform::detail {

SplineWeights::SplineWeights(const std::vector<Eigen::Vector3d>& control_m) {
  const auto n = static_cast<Eigen::Index>(control_m.size());
  // Centred and scaled to a unit radius: the kernel's entries r^3 and the polynomial's (1, x) are then
  // of one size, and the interpolant is the same (r^3 scales by a constant, the linear part absorbs the
  // shift).
  centre_m_.setZero();
  for (const auto& c : control_m) centre_m_ += c;
  centre_m_ /= static_cast<double>(n);
  double radius_m = 0;
  for (const auto& c : control_m) radius_m = std::max(radius_m, (c - centre_m_).norm());
  scale_per_m_ = radius_m > 0 ? 1.0 / radius_m : 1.0;
  control_.reserve(control_m.size());
  for (const auto& c : control_m) control_.push_back((c - centre_m_) * scale_per_m_);

  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n + 4, n + 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& ci = control_[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < i; ++j) {
      const double r = (ci - control_[static_cast<std::size_t>(j)]).norm();
      system(i, j) = system(j, i) = r * r * r;
    }
    system(i, n) = system(n, i) = 1.0;
    for (int d = 0; d < 3; ++d) system(i, n + 1 + d) = system(n + 1 + d, i) = ci[d];
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(system);
  if (lu.rank() < n + 4)
    throw InputError("skin: spline needs control points that span three dimensions (" +
                     std::to_string(control_m.size()) + " points; the system has rank " +
                     std::to_string(lu.rank()) + " of " + std::to_string(n + 4) + ")");
  // The inverse is symmetric, so its first N rows applied to [phi(v); 1; v] are the weights.
  inverse_rows_ = lu.inverse().topRows(n);
}

void SplineWeights::weigh(const Eigen::Vector3d& v_m, double* weight) const {
  const auto n = static_cast<Eigen::Index>(control_.size());
  const Eigen::Vector3d v = (v_m - centre_m_) * scale_per_m_;
  Eigen::VectorXd basis(n + 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r = (v - control_[static_cast<std::size_t>(i)]).norm();
    basis[i] = r * r * r;
  }
  basis[n] = 1.0;
  basis.tail<3>() = v;
  Eigen::Map<Eigen::VectorXd>(weight, n) = inverse_rows_ * basis;
}

}  // namespace deform::detail
