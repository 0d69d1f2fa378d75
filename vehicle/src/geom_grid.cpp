// GeomGrid (geom_grid.hpp): the space's geoms, their boxes, and a BoxGrid over the bounded ones.
#include "geom_grid.hpp"

#include <algorithm>
#include <cmath>

namespace vehicle::ode {
namespace {

constexpr double kCellMin_m = 4.0;  // a car's length: a wheel's ray box touches one to four cells

bool bounded(const std::array<dReal, 6>& b) {
  return std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]) && std::isfinite(b[3]);
}

}  // namespace

void GeomGrid::build(dSpaceID space) {
  const int count = dSpaceGetNumGeoms(space);
  geoms_.resize(static_cast<std::size_t>(count));
  boxes_.resize(static_cast<std::size_t>(count));
  everywhere_.clear();
  bucketed_.clear();
  std::vector<Box> local;
  for (int i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    geoms_[k] = dSpaceGetGeom(space, i);
    auto& b = boxes_[k];
    if (dGeomGetClass(geoms_[k]) == dPlaneClass) {
      b = {-HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL};
    } else {
      dGeomGetAABB(geoms_[k], b.data());
    }
    if (!bounded(b)) {
      everywhere_.push_back(i);
      continue;
    }
    bucketed_.push_back(i);
    local.push_back({Eigen::Vector3d(b[0], b[2], b[4]), Eigen::Vector3d(b[1], b[3], b[5])});
  }
  grid_.build(local, kCellMin_m);
}

void GeomGrid::candidates(const Eigen::Vector3d& lo_m, const Eigen::Vector3d& hi_m,
                          std::vector<int>& out) const {
  grid_.near({lo_m, hi_m}, scratch_);
  out.clear();
  for (const uint32_t k : scratch_) out.push_back(bucketed_[k]);  // ascending, as bucketed_ is
  const auto middle = static_cast<std::ptrdiff_t>(out.size());
  out.insert(out.end(), everywhere_.begin(), everywhere_.end());
  std::inplace_merge(out.begin(), out.begin() + middle, out.end());
}

void GeomGrid::pairs(std::vector<uint64_t>& out) {
  grid_.pairs(grid_pairs_);
  out.clear();
  for (const uint64_t p : grid_pairs_)  // grid items to geoms: both ascending, so still i < j
    out.push_back(uint64_t(static_cast<uint32_t>(bucketed_[p >> 32])) << 32 |
                  static_cast<uint32_t>(bucketed_[p & 0xffffffffu]));
  auto key = [](int a, int b) {
    return (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint64_t>(std::max(a, b));
  };
  for (const int e : everywhere_)
    for (int i = 0; i < static_cast<int>(geoms_.size()); ++i)
      if (i != e) out.push_back(key(e, i));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace vehicle::ode
