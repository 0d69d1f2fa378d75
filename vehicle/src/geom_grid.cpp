// GeomGrid (geom_grid.hpp): a counting sort of the geoms' boxes into grid cells.
#include "geom_grid.hpp"

#include <algorithm>
#include <cmath>

namespace vehicle::ode {
namespace {

constexpr double kCellMin_m = 4.0;  // a car's length: a wheel's ray box touches one to four cells
constexpr int kMostCellsPerAxis = 256;
constexpr int kMostCellsPerGeom = 64;  // a longer wall or a fallen tree is a candidate everywhere

bool bounded(const std::array<dReal, 6>& b) {
  return std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]) && std::isfinite(b[3]);
}

}  // namespace

namespace {

/// The cell of coordinate t (in cells from the grid's corner) among `count`, clamped; NaN and the
/// infinities too, which a cast to int would leave undefined.
int cellOf(double t, int count) {
  if (!(t >= 1)) return 0;
  if (!(t < count)) return count - 1;
  return static_cast<int>(t);
}

}  // namespace

int GeomGrid::cellX(double x_m) const {
  return cellOf((x_m - x0_m_) / cell_m_, nx_);
}

int GeomGrid::cellY(double y_m) const {
  return cellOf((y_m - y0_m_) / cell_m_, ny_);
}

void GeomGrid::build(dSpaceID space) {
  const int count = dSpaceGetNumGeoms(space);
  geoms_.resize(static_cast<std::size_t>(count));
  boxes_.resize(static_cast<std::size_t>(count));
  everywhere_.clear();
  double lo_x = HUGE_VAL, lo_y = HUGE_VAL, hi_x = -HUGE_VAL, hi_y = -HUGE_VAL;
  for (int i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    geoms_[k] = dSpaceGetGeom(space, i);
    auto& b = boxes_[k];
    if (dGeomGetClass(geoms_[k]) == dPlaneClass) {
      b = {-HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL};
      continue;
    }
    dGeomGetAABB(geoms_[k], b.data());
    if (!bounded(b)) continue;
    lo_x = std::min(lo_x, b[0]);
    hi_x = std::max(hi_x, b[1]);
    lo_y = std::min(lo_y, b[2]);
    hi_y = std::max(hi_y, b[3]);
  }
  if (!(lo_x <= hi_x)) lo_x = hi_x = lo_y = hi_y = 0;
  x0_m_ = lo_x;
  y0_m_ = lo_y;
  cell_m_ = std::max({kCellMin_m, (hi_x - lo_x) / kMostCellsPerAxis, (hi_y - lo_y) / kMostCellsPerAxis});
  nx_ = std::max(1, static_cast<int>(std::ceil((hi_x - lo_x) / cell_m_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((hi_y - lo_y) / cell_m_)));
  nx_ = std::min(nx_, kMostCellsPerAxis + 1);
  ny_ = std::min(ny_, kMostCellsPerAxis + 1);

  // Two passes (count, then fill) over the geoms that a few cells hold, in index order: each cell's list
  // comes out ascending.
  cell_start_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
  auto forCells = [&](int i, auto&& visit) {
    const auto& b = boxes_[static_cast<std::size_t>(i)];
    const int x0 = cellX(b[0]), x1 = cellX(b[1]), y0 = cellY(b[2]), y1 = cellY(b[3]);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) visit(static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + x);
  };
  std::vector<uint8_t> local(static_cast<std::size_t>(count), 0);
  for (int i = 0; i < count; ++i) {
    const auto& b = boxes_[static_cast<std::size_t>(i)];
    const bool few =
        bounded(b) && (cellX(b[1]) - cellX(b[0]) + 1) * (cellY(b[3]) - cellY(b[2]) + 1) <= kMostCellsPerGeom;
    if (!few) {
      everywhere_.push_back(i);
      continue;
    }
    local[static_cast<std::size_t>(i)] = 1;
    forCells(i, [&](std::size_t c) { ++cell_start_[c + 1]; });
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_items_.resize(static_cast<std::size_t>(cell_start_.back()));
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < count; ++i)
    if (local[static_cast<std::size_t>(i)])
      forCells(i, [&](std::size_t c) { cell_items_[static_cast<std::size_t>(fill[c]++)] = i; });
}

void GeomGrid::candidates(const Eigen::Vector3d& lo_m, const Eigen::Vector3d& hi_m,
                          std::vector<int>& out) const {
  out.assign(everywhere_.begin(), everywhere_.end());
  const int x0 = cellX(lo_m.x()), x1 = cellX(hi_m.x()), y0 = cellY(lo_m.y()), y1 = cellY(hi_m.y());
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const std::size_t c =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x);
      out.insert(out.end(), cell_items_.begin() + cell_start_[c], cell_items_.begin() + cell_start_[c + 1]);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

void GeomGrid::pairs(std::vector<uint64_t>& out) const {
  out.clear();
  auto key = [](int a, int b) {
    return (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint64_t>(std::max(a, b));
  };
  for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c)
    for (int p = cell_start_[c]; p < cell_start_[c + 1]; ++p)
      for (int q = p + 1; q < cell_start_[c + 1]; ++q)
        out.push_back(
            key(cell_items_[static_cast<std::size_t>(p)], cell_items_[static_cast<std::size_t>(q)]));
  for (const int e : everywhere_)
    for (int i = 0; i < static_cast<int>(geoms_.size()); ++i)
      if (i != e) out.push_back(key(e, i));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace vehicle::ode
