#pragma once
// Axis-aligned boxes in the world for the broad phases of Simulation's step: which cars are idle
// (simulation_step.cpp) and what a car's body can reach within a step (crush_coupling.cpp).
#include <vehicle/obstacle_shape.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace vehicle {

/// An axis-aligned box [m].
struct Box {
  Eigen::Vector3d min_m{0, 0, 0}, max_m{0, 0, 0};
  bool overlaps(const Box& o) const {
    return (min_m.array() <= o.max_m.array()).all() && (o.min_m.array() <= max_m.array()).all();
  }
  Box grown(double grow_m) const { return {min_m.array() - grow_m, max_m.array() + grow_m}; }
  /// Half the diagonal [m].
  double halfDiagonal_m() const { return 0.5 * (max_m - min_m).norm(); }
};

/// Boxes bucketed by their x-y extent on a uniform grid (cells at least `cell_min_m` wide, at most 256 a
/// side): the boxes that may come within reach of one, in ascending index, without testing all of them.
class BoxGrid {
 public:
  void build(const std::vector<Box>& boxes, double cell_min_m);
  /// Every box whose cells meet those of `box` (a superset of the boxes overlapping it), ascending.
  void near(const Box& box, std::vector<uint32_t>& out) const;
  /// Every pair (i < j) of boxes that share a cell (a superset of the pairs that overlap), as
  /// i << 32 | j, ascending.
  void pairs(std::vector<uint64_t>& out) const;

 private:
  double x0_m_ = 0, y0_m_ = 0, cell_m_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<uint32_t> start_, items_;  ///< cell c holds items_[start_[c] .. start_[c + 1])
  int cell(double t, int count) const;
};

/// The box around `points_m` (not empty).
Box boxOf(const std::vector<Eigen::Vector3d>& points_m);
/// The box around a shape (its support points along the axes); not a half-space.
Box boxOf(const ObstacleShape& shape);

}  // namespace vehicle
