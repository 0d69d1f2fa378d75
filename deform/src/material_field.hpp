#pragma once
// The body's material as a field over its skin (body_settings.cpp): a region selected by a box is the
// part of the skin inside the box, not the control points inside it, so a constraint takes the share of
// each material over the skin it stands for and the material map does not move with the level of detail.
#include <deform/body_settings.hpp>

#include <Eigen/Core>
#include <vector>

namespace deform::detail {

/// Shares of each material (index 0 = the body's default, r + 1 = region r) in one constraint's patch of
/// skin; they sum to 1.
using MaterialShares = std::vector<double>;

class MaterialField {
 public:
  explicit MaterialField(const std::vector<MaterialRegion>& regions);

  /// Whether any region is selected by a box (otherwise every place is the default material).
  bool hasBoxes() const { return has_boxes_; }
  /// Material index at a place on the skin: the last region whose box holds it, else 0.
  uint32_t at(const Eigen::Vector3d& place_m) const;

  /// Adds triangle (a, b, c)'s skin to `shares` (unnormalised, in m^2): sampled at the centroids of a
  /// regular subdivision (exact for a weight linear over the triangle). With `hat_corner` 0, 1 or 2 each
  /// sample is weighted by that corner's barycentric coordinate (a control point's third of the
  /// triangle); with -1, uniformly.
  void addTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   int hat_corner, MaterialShares& shares) const;

  /// The material of every place in the box from `low_m` to `high_m`, or -1 when the box holds more than one.
  int uniformOver(const Eigen::Vector3d& low_m, const Eigen::Vector3d& high_m) const;

  /// `shares` scaled to sum to 1; all default when they hold no area (a degenerate patch).
  static void normalise(MaterialShares& shares);
  /// The index with the largest share (the first of equal ones).
  static uint32_t dominant(const MaterialShares& shares);

 private:
  std::vector<MaterialRegion> regions_;
  bool has_boxes_ = false;
};

}  // namespace deform::detail
