#pragma once
// The front profile of a car after a frontal crash: the front-most vertex x in each slice across the
// width, as a plan view of the crushed front (a flat wall leaves a flat front; a skin that cannot follow
// the control points leaves a wavy one).
#include <deform/mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace sandbox::figures {

struct FrontProfile {
  std::vector<double> y_m;        ///< slice centres across the width [m] (vehicle frame, +y left)
  std::vector<double> front_x_m;  ///< front-most vertex x in each slice [m] (NaN for an empty slice)
  /// max - min of front_x_m over the slices whose centre lies in the middle `middle_fraction` of the
  /// width [m].
  double variation_m = 0;
};

/// Slices of `slice_m` across the width of `box` (the car at rest), each holding the vertices of
/// `positions_m` whose y falls in it.
FrontProfile frontProfile(const std::vector<Eigen::Vector3f>& positions_m, const deform::Aabb& box,
                          double slice_m = 0.1, double middle_fraction = 0.8);

}  // namespace sandbox::figures
