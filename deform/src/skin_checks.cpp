// Measures of a skin: affine reproduction and the spread of the weights.
#include <deform/skin_checks.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace deform {

AffineMap crashSizedAffineMap(const Eigen::Vector3d& centre_m) {
  const double angle_rad = 12.0 * M_PI / 180.0;
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(angle_rad, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  const Eigen::Matrix3d stretch = Eigen::Vector3d(0.85, 1.10, 1.05).asDiagonal();
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear(0, 2) = 0.12;  // x shifts with height: a front pushed back at the roof
  AffineMap map;
  map.linear = rotation * stretch * shear;
  map.centre_m = centre_m;
  map.translation_m = Eigen::Vector3d(0.3, -0.2, 0.2);
  return map;
}

double affineReproductionErrorMax(const Skin& skin, const std::vector<Eigen::Vector3f>& vertices_m,
                                  const std::vector<Eigen::Vector3d>& control_rest_m, const AffineMap& map,
                                  unsigned threads) {
  std::vector<Eigen::Vector3d> displacement_m(control_rest_m.size());
  for (std::size_t i = 0; i < control_rest_m.size(); ++i)
    displacement_m[i] = map(control_rest_m[i]) - control_rest_m[i];
  std::vector<Eigen::Vector3f> moved_m(vertices_m.size());
  skin.deform(vertices_m.data(), displacement_m.data(), moved_m.data(), threads);
  double worst_m = 0;
  for (std::size_t j = 0; j < vertices_m.size(); ++j)
    worst_m = std::max(worst_m, (moved_m[j].cast<double>() - map(vertices_m[j].cast<double>())).norm());
  return worst_m;
}

SkinWeightSpread skinWeightSpread(const Skin& skin) {
  SkinWeightSpread spread;
  std::size_t used = 0, negative = 0;
  for (std::size_t j = 0; j < skin.vertexCount(); ++j) {
    for (std::size_t k = 0; k < skin.influences(); ++k) {
      const double w = skin.slotWeight(j, k);
      if (w == 0) continue;
      ++used;
      negative += w < 0;
      spread.largest_abs_weight = std::max(spread.largest_abs_weight, std::abs(w));
      spread.smallest_weight = std::min(spread.smallest_weight, w);
    }
  }
  spread.negative_fraction = used ? static_cast<double>(negative) / static_cast<double>(used) : 0.0;
  return spread;
}

}  // namespace deform
