// Weights of one render vertex over its K nearest control points (deform/skin.hpp).
#include "skin_weights.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace deform::detail {

void inverseDistanceWeights(const double* distance_m, std::size_t count, double alpha, double* weight) {
  // phi_i = 1/d_i^alpha is evaluated as (d_min/d_i)^alpha, which is 1 for the nearest point and never
  // overflows, whatever alpha or however close the vertex sits to a control point.
  const double d_min = *std::min_element(distance_m, distance_m + count);
  double sum = 0;
  for (std::size_t k = 0; k < count; ++k) {
    weight[k] = d_min > 0 ? std::pow(d_min / distance_m[k], alpha) : (distance_m[k] == 0 ? 1.0 : 0.0);
    sum += weight[k];
  }
  for (std::size_t k = 0; k < count; ++k) weight[k] /= sum;  // sum >= 1: the nearest contributes 1
}

bool movingLeastSquaresWeights(const Eigen::Vector3d& v_m, const Eigen::Vector3d* point_m,
                               const double* distance_m, std::size_t count, double alpha, double* weight,
                               double cutoff_m) {
  // theta_k: the inverse-distance weights, normalised (sum 1). On a control point they are already the
  // interpolant (that point alone), and the affine fit below adds nothing.
  inverseDistanceWeights(distance_m, count, alpha, weight);
  if (*std::min_element(distance_m, distance_m + count) == 0) return true;
  if (cutoff_m > 0) {
    // Less the weight the next point out would have (at cutoff_m), so that a point's weight falls to zero
    // as it leaves the K nearest: the fit, and so the deformed surface, is continuous where the set of
    // nearest points changes. Without it the fit jumped there and left creases on a dented 200k-vertex
    // bumper (docs/TRADEOFF.md). A point swapped in from further (widenSpan) keeps its own weight.
    // Points all as far as the next one (a symmetric set, within rounding) would leave nothing: the
    // plain weights stay then.
    const double d_min = *std::min_element(distance_m, distance_m + count);
    const double beyond = std::pow(d_min / cutoff_m, alpha);
    thread_local std::vector<double> cut;
    cut.resize(count);
    double sum = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const double phi = std::pow(d_min / distance_m[k], alpha);
      cut[k] = distance_m[k] < cutoff_m ? phi - beyond : phi;
      sum += cut[k];
    }
    if (sum > 0)
      for (std::size_t k = 0; k < count; ++k) weight[k] = cut[k] / sum;
  }

  // Schaefer, McPhail & Warren 2006, equations (4)-(5), affine map, written for weights: with
  //   p* = sum_k theta_k p_k,  p^_k = p_k - p*,  M = sum_k theta_k p^_k p^_k^T,
  // the affine fit of the displacements evaluated at v is sum_k A_k d_k with
  //   A_k = theta_k (1 + (v - p*)^T M^-1 p^_k).
  // Then sum_k A_k = 1 and sum_k A_k p_k = p* + M M^-1 (v - p*) = v (Levin 1998: linear precision).
  // Round-off: everything is taken relative to the nearest point r (the one with the most weight),
  //   p^_k = (p_k - r) - sum_l theta_l (p_l - r),  v - p* = (v - r) - sum_l theta_l (p_l - r),
  // never as the difference of two absolute positions: when r holds nearly all the weight, p^_r is tiny
  // and p_r - p* would lose every digit of it.
  const std::size_t nearest =
      static_cast<std::size_t>(std::min_element(distance_m, distance_m + count) - distance_m);
  const Eigen::Vector3d& r_m = point_m[nearest];
  Eigen::Vector3d centroid_from_r_m = Eigen::Vector3d::Zero();
  double reach_m2 = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (k != nearest) centroid_from_r_m += weight[k] * (point_m[k] - r_m);
    reach_m2 = std::max(reach_m2, distance_m[k] * distance_m[k]);
  }
  const Eigen::Vector3d offset_m = (v_m - r_m) - centroid_from_r_m;  // v - p*
  thread_local std::vector<Eigen::Vector3d> p_hat_m;                 // scratch: no allocation per vertex
  p_hat_m.resize(count);
  for (std::size_t k = 0; k < count; ++k)
    p_hat_m[k] = k == nearest ? Eigen::Vector3d(-centroid_from_r_m)
                              : Eigen::Vector3d((point_m[k] - r_m) - centroid_from_r_m);
  Eigen::Matrix3d moment_m2 = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < count; ++k) moment_m2 += weight[k] * p_hat_m[k] * p_hat_m[k].transpose();
  // Pseudo-inverse: directions whose spread is round-off next to the largest (flat or collinear points)
  // are left out, so linear precision holds in the directions the points span; the absolute floor keeps
  // 1 / lambda finite when nearly all the weight sits on one point (M vanishes with the others' weights).
  constexpr double kRoundOffSpread = 1e-10;  // [-] of the largest eigenvalue
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(moment_m2);
  const Eigen::Vector3d lambda_m2 = eigen.eigenvalues();  // ascending
  const double floor_m2 = std::max(kRoundOffSpread * lambda_m2[2], 1e-30 * reach_m2);
  Eigen::Matrix3d inverse_per_m2 = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 3; ++a) {
    if (!(lambda_m2[a] > floor_m2)) continue;
    const Eigen::Vector3d u = eigen.eigenvectors().col(a);
    inverse_per_m2 += (u / lambda_m2[a]) * u.transpose();
  }
  const Eigen::RowVector3d offset_per_m = offset_m.transpose() * inverse_per_m2;
  // The fit's change to the inverse-distance weights, delta_k = theta_k (v - p*)^T M^-1 p^_k (sum 0).
  thread_local std::vector<double> delta;
  delta.resize(count);
  double delta_abs_sum = 0;
  for (std::size_t k = 0; k < count; ++k) {
    delta[k] = weight[k] * offset_per_m.dot(p_hat_m[k]);
    if (!std::isfinite(delta[k])) return false;  // not expected with the floor above: the inverse distances
    delta_abs_sum += std::abs(delta[k]);
  }
  // Bounded extrapolation: a vertex far outside a thin (nearly flat) set of points would need weights in
  // the thousands, which amplify any non-affine wobble of those points and the float rounding of the
  // weights. There the fit is applied only in part, so that sum_k |w_k| <= kMaxWeightAbsSum: continuous in
  // the vertex, still summing to 1, exact wherever the bound is not reached (everywhere on the built-in
  // sedan at K = 8 and N = 60, 250 or 1000: largest |w| 1.2 at N = 60; K = 4 reaches it on a few vertices).
  constexpr double kMaxWeightAbsSum = 20.0;  // [-]
  const double share = std::min(1.0, (kMaxWeightAbsSum - 1.0) / std::max(delta_abs_sum, 1e-300));
  for (std::size_t k = 0; k < count; ++k) weight[k] += share * delta[k];
  return share >= 1.0;
}

namespace {

/// The plane of the chosen points: their mean [m], the unit direction across which they spread least,
/// their standard deviation across it and along their widest direction [m].
struct PointSpread {
  Eigen::Vector3d mean_m;
  Eigen::Vector3d thinnest;
  double thickness_m;
  double extent_m;
};

PointSpread pointSpread(const std::vector<Eigen::Vector3d>& control_m,
                        const std::vector<RankedPoint>& chosen) {
  PointSpread s;
  s.mean_m.setZero();
  for (const auto& c : chosen) s.mean_m += control_m[c.index];
  s.mean_m /= static_cast<double>(chosen.size());
  Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();
  for (const auto& c : chosen) {
    const Eigen::Vector3d d = control_m[c.index] - s.mean_m;
    covariance_m2 += d * d.transpose() / static_cast<double>(chosen.size());
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance_m2);
  s.thinnest = eigen.eigenvectors().col(0);
  s.thickness_m = std::sqrt(std::max(eigen.eigenvalues()[0], 0.0));
  s.extent_m = std::sqrt(std::max(eigen.eigenvalues()[2], 0.0));
  return s;
}

bool outOfSpan(const Eigen::Vector3d& v_m, const PointSpread& s) {
  return std::abs((v_m - s.mean_m).dot(s.thinnest)) > 3.0 * s.thickness_m + 1e-9 * s.extent_m;
}

}  // namespace

bool offsetOutOfSpan(const Eigen::Vector3d& v_m, const std::vector<Eigen::Vector3d>& control_m,
                     const std::vector<RankedPoint>& chosen) {
  return chosen.size() >= 4 && outOfSpan(v_m, pointSpread(control_m, chosen));
}

bool widenSpan(const Eigen::Vector3d& v_m, const std::vector<Eigen::Vector3d>& control_m,
               std::vector<RankedPoint>& chosen, const std::vector<RankedPoint>& candidates, bool thick) {
  uint32_t added[2] = {0, 0};
  PointSpread s = pointSpread(control_m, chosen);
  for (int swap = 0; swap < 2 && chosen.size() >= 4; ++swap) {
    if (!(thick && swap == 0) && !outOfSpan(v_m, s)) return true;
    const double offset_m = thick ? std::max(std::abs((v_m - s.mean_m).dot(s.thinnest)), 2.0 * s.extent_m)
                                  : std::abs((v_m - s.mean_m).dot(s.thinnest));
    const RankedPoint* found = nullptr;
    for (const RankedPoint& c : candidates) {
      const bool taken =
          std::any_of(chosen.begin(), chosen.end(), [&](const RankedPoint& o) { return o.index == c.index; });
      if (!taken && std::abs((control_m[c.index] - s.mean_m).dot(s.thinnest)) >= 0.5 * offset_m) {
        found = &c;
        break;
      }
    }
    if (!found) return false;
    // The farthest of the points not swapped in leaves (a point just added is never swapped out again).
    RankedPoint* leaving = nullptr;
    for (RankedPoint& c : chosen) {
      const bool was_added = std::find(added, added + swap, c.index) != added + swap;
      if (!was_added && (!leaving || *leaving < c)) leaving = &c;
    }
    const RankedPoint before = *leaving;
    *leaving = *found;
    const PointSpread widened = pointSpread(control_m, chosen);
    if (widened.thickness_m <= s.thickness_m) {  // flat again another way: keep what there was
      *leaving = before;
      return true;
    }
    added[swap] = found->index;
    s = widened;
  }
  return true;
}

}  // namespace deform::detail
