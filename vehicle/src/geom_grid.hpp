#pragma once
// The space's geoms bucketed by their boxes on a uniform grid in x and y, built once per step before the
// wheels cast their rays (no body moves while they do, nor until ODE's collision pass): a ray's
// candidates are the geoms in the cells its box covers, and the collision pass's are the pairs that share
// a cell, not every geom and every pair in the space. With 200 cars every wheel's ray had tested every
// geom's box, half of the step's time, and ODE's simple space every pair of boxes, a sixth of it
// (docs/BENCHMARKS.md, "Many cars"). Both come out in the space's order, so the results are the same to
// the bit.
#include "broad_phase.hpp"

#include <ode/ode.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace vehicle::ode {

class GeomGrid {
 public:
  /// Buckets every geom of `space` by its box (vehicle::BoxGrid); planes and geoms with an unbounded box
  /// are candidates everywhere.
  void build(dSpaceID space);
  /// The geoms whose boxes may meet the box [lo, hi], in the space's order (ascending index), each once.
  void candidates(const Eigen::Vector3d& lo_m, const Eigen::Vector3d& hi_m, std::vector<int>& out) const;
  /// Every pair (i < j) of geoms that share a cell, or of which one is everywhere, as i << 32 | j,
  /// ascending in (i, j): the order ODE's simple space meets them in.
  void pairs(std::vector<uint64_t>& out);
  dGeomID geom(int index) const { return geoms_[static_cast<std::size_t>(index)]; }
  /// The box ODE gave geom `index` when the grid was built: min x, max x, min y, max y, min z, max z.
  const std::array<dReal, 6>& box(int index) const { return boxes_[static_cast<std::size_t>(index)]; }

 private:
  std::vector<dGeomID> geoms_;
  std::vector<std::array<dReal, 6>> boxes_;
  std::vector<int> everywhere_;  ///< ascending
  std::vector<int> bucketed_;    ///< the grid's item k is geom bucketed_[k] (ascending)
  BoxGrid grid_;
  mutable std::vector<uint32_t> scratch_;
  std::vector<uint64_t> grid_pairs_;
};

/// Whether two boxes as ODE gives them (min x, max x, min y, max y, min z, max z) meet.
inline bool boxesMeet(const std::array<dReal, 6>& a, const std::array<dReal, 6>& b) {
  return !(a[0] > b[1] || a[1] < b[0] || a[2] > b[3] || a[3] < b[2] || a[4] > b[5] || a[5] < b[4]);
}

}  // namespace vehicle::ode
