#pragma once
// Measures of a skin (deform/skin.hpp): how far it is from reproducing an affine motion of its control
// points, and the spread of its weights (negative weights extrapolate; large ones amplify noise).
#include <deform/skin.hpp>

#include <Eigen/Core>
#include <vector>

namespace deform {

/// x -> centre + linear (x - centre) + translation, positions in metres.
struct AffineMap {
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();     ///< [-]
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();       ///< [m]
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();  ///< [m]
  /// The map applied to `x_m` [m].
  Eigen::Vector3d operator()(const Eigen::Vector3d& x_m) const {
    return centre_m + linear * (x_m - centre_m) + translation_m;
  }
};

/// A fixed affine map of a crash's size about `centre_m`: a 12 degree rotation about a tilted axis, axial
/// strains of -15 %, +10 % and +5 %, a shear of 0.12 and a translation of 0.4 m.
AffineMap crashSizedAffineMap(const Eigen::Vector3d& centre_m);

/// Largest |skinned vertex - map(vertex)| [m] over the vertices when every control point c_i0 moves to
/// map(c_i0). Zero for a skin with linear precision (up to float round-off); the idw skin is not.
double affineReproductionErrorMax(const Skin& skin, const std::vector<Eigen::Vector3f>& vertices_m,
                                  const std::vector<Eigen::Vector3d>& control_rest_m, const AffineMap& map,
                                  unsigned threads = 0);

/// How far a skin's weights stray from [0, 1] (mls weights may be negative).
struct SkinWeightSpread {
  double largest_abs_weight = 0;  ///< max |w_ij| over all slots [-] (1 at most for idw)
  double smallest_weight = 0;     ///< min w_ij [-] (>= 0 for idw)
  double negative_fraction = 0;   ///< share of the used slots (w != 0) whose weight is below zero [-]
};

/// The spread of every used slot's weight of `skin`.
SkinWeightSpread skinWeightSpread(const Skin& skin);

}  // namespace deform
