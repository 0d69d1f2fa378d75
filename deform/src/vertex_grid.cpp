// The uniform grid over rest positions (vertex_grid.hpp): counting sort into cells.
#include <deform/vertex_grid.hpp>

#include <algorithm>
#include <cmath>

namespace deform {

VertexGrid::VertexGrid(const std::vector<Eigen::Vector3f>& rest_m, double per_cell) {
  build(rest_m, per_cell);
}

VertexGrid::VertexGrid(const std::vector<Eigen::Vector3d>& rest_m, double per_cell) {
  build(rest_m, per_cell);
}

template <class Point>
void VertexGrid::build(const std::vector<Point>& rest_m, double per_cell) {
  if (rest_m.empty()) return;
  bounds_.min_m = bounds_.max_m = rest_m[0].template cast<double>();
  for (const Point& p : rest_m) {
    bounds_.min_m = bounds_.min_m.cwiseMin(p.template cast<double>());
    bounds_.max_m = bounds_.max_m.cwiseMax(p.template cast<double>());
  }
  // Cubic cells sized for `per_cell` vertices if they filled the box; a thin box (a flat test grid)
  // would get cells far larger than its thickness, so the edge is taken over the extents that are not
  // degenerate. At most 128 cells along an axis.
  const Eigen::Vector3d size = bounds_.size_m();
  const double floor_m = 1e-6 * std::max(size.maxCoeff(), 1e-9);
  double volume = 1;
  int dims = 0;
  for (int k = 0; k < 3; ++k)
    if (size[k] > floor_m) volume *= size[k], ++dims;
  const double cells_wanted = std::max(1.0, static_cast<double>(rest_m.size()) / std::max(per_cell, 1.0));
  cell_m_ = dims == 0 ? 1.0 : std::pow(volume / cells_wanted, 1.0 / dims);
  for (int k = 0; k < 3; ++k) cells_[k] = std::clamp(static_cast<int>(std::ceil(size[k] / cell_m_)), 1, 128);
  cell_m_ = std::max({cell_m_, size.x() / cells_.x(), size.y() / cells_.y(), size.z() / cells_.z()});
  const std::size_t count = static_cast<std::size_t>(cells_.x()) * cells_.y() * cells_.z();
  cell_begin_.assign(count + 1, 0);
  std::vector<uint32_t> cell_of(rest_m.size());
  for (std::size_t v = 0; v < rest_m.size(); ++v) {
    const Eigen::Vector3i c = cellOf(rest_m[v].template cast<double>());
    cell_of[v] = static_cast<uint32_t>((c.z() * cells_.y() + c.y()) * cells_.x() + c.x());
    ++cell_begin_[cell_of[v] + 1];
  }
  for (std::size_t c = 0; c < count; ++c) cell_begin_[c + 1] += cell_begin_[c];
  vertices_.resize(rest_m.size());
  std::vector<uint32_t> fill(cell_begin_.begin(), cell_begin_.end() - 1);
  for (std::size_t v = 0; v < rest_m.size(); ++v) vertices_[fill[cell_of[v]]++] = static_cast<uint32_t>(v);
}

Eigen::Vector3i VertexGrid::cellOf(const Eigen::Vector3d& p_m) const {
  Eigen::Vector3i c;
  for (int k = 0; k < 3; ++k)
    // Clamped as a double first: a far point (a reach of 1e10 m) would overflow the int.
    c[k] = static_cast<int>(std::clamp(std::floor((p_m[k] - bounds_.min_m[k]) / cell_m_), 0.0,
                                       static_cast<double>(cells_[k] - 1)));
  return c;
}

std::size_t VertexGrid::query(const Aabb& box, std::vector<uint32_t>& out) const {
  if (vertices_.empty() || !(box.min_m.array() <= bounds_.max_m.array()).all() ||
      !(box.max_m.array() >= bounds_.min_m.array()).all())
    return 0;
  const Eigen::Vector3i lo = cellOf(box.min_m), hi = cellOf(box.max_m);
  const std::size_t before = out.size();
  for (int z = lo.z(); z <= hi.z(); ++z)
    for (int y = lo.y(); y <= hi.y(); ++y) {
      const std::size_t row = static_cast<std::size_t>(z * cells_.y() + y) * cells_.x();
      out.insert(out.end(), vertices_.begin() + cell_begin_[row + lo.x()],
                 vertices_.begin() + cell_begin_[row + hi.x() + 1]);
    }
  return out.size() - before;
}

}  // namespace deform
