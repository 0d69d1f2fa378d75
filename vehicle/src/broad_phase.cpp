#include "broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace vehicle {

int BoxGrid::cell(double t, int count) const {
  if (!(t >= 1)) return 0;  // NaN and -inf too
  if (!(t < count)) return count - 1;
  return static_cast<int>(t);
}

void BoxGrid::build(const std::vector<Box>& boxes, double cell_min_m) {
  constexpr int kMostCells = 256;
  double lo_x = HUGE_VAL, lo_y = HUGE_VAL, hi_x = -HUGE_VAL, hi_y = -HUGE_VAL;
  for (const Box& b : boxes) {
    lo_x = std::min(lo_x, b.min_m.x());
    lo_y = std::min(lo_y, b.min_m.y());
    hi_x = std::max(hi_x, b.max_m.x());
    hi_y = std::max(hi_y, b.max_m.y());
  }
  if (!(lo_x <= hi_x && lo_y <= hi_y && std::isfinite(hi_x - lo_x) && std::isfinite(hi_y - lo_y)))
    lo_x = hi_x = lo_y = hi_y = 0;  // none, or not finite: one cell holds them all
  x0_m_ = lo_x;
  y0_m_ = lo_y;
  cell_m_ = std::max({cell_min_m, (hi_x - lo_x) / kMostCells, (hi_y - lo_y) / kMostCells, 1e-9});
  nx_ = std::clamp(static_cast<int>(std::ceil((hi_x - lo_x) / cell_m_)), 1, kMostCells + 1);
  ny_ = std::clamp(static_cast<int>(std::ceil((hi_y - lo_y) / cell_m_)), 1, kMostCells + 1);
  start_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
  auto visit = [&](const Box& b, auto&& fn) {
    const int x0 = cell((b.min_m.x() - x0_m_) / cell_m_, nx_),
              x1 = cell((b.max_m.x() - x0_m_) / cell_m_, nx_);
    const int y0 = cell((b.min_m.y() - y0_m_) / cell_m_, ny_),
              y1 = cell((b.max_m.y() - y0_m_) / cell_m_, ny_);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) fn(static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + x);
  };
  for (const Box& b : boxes) visit(b, [&](std::size_t c) { ++start_[c + 1]; });
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  items_.resize(start_.back());
  std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
  for (uint32_t i = 0; i < boxes.size(); ++i) visit(boxes[i], [&](std::size_t c) { items_[fill[c]++] = i; });
}

void BoxGrid::near(const Box& box, std::vector<uint32_t>& out) const {
  out.clear();
  const int x0 = cell((box.min_m.x() - x0_m_) / cell_m_, nx_),
            x1 = cell((box.max_m.x() - x0_m_) / cell_m_, nx_);
  const int y0 = cell((box.min_m.y() - y0_m_) / cell_m_, ny_),
            y1 = cell((box.max_m.y() - y0_m_) / cell_m_, ny_);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const std::size_t c =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x);
      out.insert(out.end(), items_.begin() + start_[c], items_.begin() + start_[c + 1]);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

void BoxGrid::pairs(std::vector<uint64_t>& out) const {
  out.clear();
  for (std::size_t c = 0; c + 1 < start_.size(); ++c)
    for (uint32_t p = start_[c]; p < start_[c + 1]; ++p)
      for (uint32_t q = p + 1; q < start_[c + 1]; ++q)  // a cell's items are ascending
        out.push_back(uint64_t{items_[p]} << 32 | items_[q]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

Box boxOf(const std::vector<Eigen::Vector3d>& points_m) {
  Box box{points_m.front(), points_m.front()};
  for (const Eigen::Vector3d& p : points_m) {
    box.min_m = box.min_m.cwiseMin(p);
    box.max_m = box.max_m.cwiseMax(p);
  }
  return box;
}

Box boxOf(const ObstacleShape& shape) {
  Box box;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d along = Eigen::Vector3d::Unit(axis);
    box.max_m[axis] = supportPoint(shape, along)[axis];
    box.min_m[axis] = supportPoint(shape, -along)[axis];
  }
  return box;
}

}  // namespace vehicle
