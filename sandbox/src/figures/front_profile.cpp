#include "front_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sandbox::figures {

FrontProfile frontProfile(const std::vector<Eigen::Vector3f>& positions_m, const deform::Aabb& box,
                          double slice_m, double middle_fraction) {
  const double y0 = box.min_m.y(), width_m = box.size_m().y();
  const auto slices = static_cast<std::size_t>(std::ceil(width_m / slice_m));
  const double none = -std::numeric_limits<double>::infinity();
  std::vector<double> front(slices, none);
  for (const auto& p : positions_m) {
    const double s = std::floor((p.y() - y0) / slice_m);
    if (s < 0 || s >= static_cast<double>(slices)) continue;
    double& x = front[static_cast<std::size_t>(s)];
    x = std::max(x, static_cast<double>(p.x()));
  }
  FrontProfile profile;
  const double centre_y = y0 + 0.5 * width_m, half_middle_m = 0.5 * middle_fraction * width_m;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t s = 0; s < slices; ++s) {
    const double y = y0 + (static_cast<double>(s) + 0.5) * slice_m;
    const double x = front[s] == none ? std::nan("") : front[s];
    profile.y_m.push_back(y);
    profile.front_x_m.push_back(x);
    if (std::abs(y - centre_y) <= half_middle_m && std::isfinite(x)) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  profile.variation_m = hi >= lo ? hi - lo : 0.0;
  return profile;
}

}  // namespace sandbox::figures
