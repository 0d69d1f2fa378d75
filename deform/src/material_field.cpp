// The material map sampled over the skin (material_field.hpp).
#include "material_field.hpp"

#include <algorithm>

namespace deform::detail {
namespace {

/// Subdivisions per triangle edge: 8 x 8 = 64 samples, so a region boundary crossing a coarse triangle
/// (0.7 m across at 60 points) is placed within about 5 cm.
constexpr int kSubdivisions = 8;

}  // namespace

MaterialField::MaterialField(const std::vector<MaterialRegion>& regions) : regions_(regions) {
  has_boxes_ = std::any_of(regions_.begin(), regions_.end(), [](const MaterialRegion& r) { return r.box_m; });
}

uint32_t MaterialField::at(const Eigen::Vector3d& place_m) const {
  for (std::size_t r = regions_.size(); r-- > 0;) {
    const auto& box = regions_[r].box_m;
    if (box && (place_m.array() >= box->min_m.array()).all() && (place_m.array() <= box->max_m.array()).all())
      return static_cast<uint32_t>(r + 1);
  }
  return 0;
}

int MaterialField::uniformOver(const Eigen::Vector3d& low_m, const Eigen::Vector3d& high_m) const {
  for (std::size_t r = regions_.size(); r-- > 0;) {
    const auto& box = regions_[r].box_m;
    if (!box || (high_m.array() < box->min_m.array()).any() || (low_m.array() > box->max_m.array()).any())
      continue;  // no place of the box's is in this region
    const bool holds =
        (low_m.array() >= box->min_m.array()).all() && (high_m.array() <= box->max_m.array()).all();
    return holds ? static_cast<int>(r + 1) : -1;
  }
  return 0;
}

void MaterialField::addTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                int hat_corner, MaterialShares& shares) const {
  const double area_m2 = 0.5 * (b - a).cross(c - a).norm();
  if (!(area_m2 > 0)) return;
  // A triangle wholly in one material needs no samples: its share is its area (a third of it under a
  // corner's hat). Refinement builds a body's constraints again for every small step of the crush, and the
  // samples were 40 % of a refined pole_side run.
  const int uniform = uniformOver(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c));
  if (uniform >= 0) {
    shares[static_cast<std::size_t>(uniform)] += hat_corner >= 0 && hat_corner <= 2 ? area_m2 / 3.0 : area_m2;
    return;
  }
  const double sub_area_m2 = area_m2 / (kSubdivisions * kSubdivisions);
  constexpr double s = 1.0 / kSubdivisions;
  // Sub-triangles of the barycentric grid: (i, j) upright and, where it fits, (i, j) inverted; each
  // sampled at its centroid in barycentric coordinates (u, v, 1 - u - v) of (a, b, c).
  auto sample = [&](double u, double v) {
    const double w = 1.0 - u - v;
    const double hat = hat_corner == 0 ? u : hat_corner == 1 ? v : hat_corner == 2 ? w : 1.0;
    shares[at(u * a + v * b + w * c)] += hat * sub_area_m2;
  };
  for (int i = 0; i < kSubdivisions; ++i)
    for (int j = 0; i + j < kSubdivisions; ++j) {
      sample((i + 1.0 / 3.0) * s, (j + 1.0 / 3.0) * s);
      if (i + j + 1 < kSubdivisions) sample((i + 2.0 / 3.0) * s, (j + 2.0 / 3.0) * s);
    }
}

void MaterialField::normalise(MaterialShares& shares) {
  double total = 0;
  for (double v : shares) total += v;
  if (!(total > 0)) {
    std::fill(shares.begin(), shares.end(), 0.0);
    shares[0] = 1.0;
    return;
  }
  for (double& v : shares) v /= total;
}

uint32_t MaterialField::dominant(const MaterialShares& shares) {
  return static_cast<uint32_t>(std::max_element(shares.begin(), shares.end()) - shares.begin());
}

}  // namespace deform::detail
