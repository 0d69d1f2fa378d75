// The lattice of a spline skin (skin_lattice.hpp).
#include "skin_lattice.hpp"

#include <algorithm>
#include <cmath>

namespace deform::detail {

BsplineLattice bsplineLattice(const std::vector<Eigen::Vector3f>& vertices_m) {
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();
  if (!vertices_m.empty()) low = high = vertices_m.front().cast<double>();
  for (const auto& v : vertices_m) {
    low = low.cwiseMin(v.cast<double>());
    high = high.cwiseMax(v.cast<double>());
  }
  const double longest_m = std::max((high - low).maxCoeff(), 1e-6);
  const double cell_m = longest_m / kLatticeCellsOnLongestSide;
  low -= Eigen::Vector3d::Constant(1e-3 * longest_m);
  high += Eigen::Vector3d::Constant(1e-3 * longest_m);
  int cells[3];
  Eigen::Vector3d step_m;
  for (int a = 0; a < 3; ++a) {
    cells[a] = std::max(1, static_cast<int>(std::ceil((high[a] - low[a]) / cell_m)));
    step_m[a] = (high[a] - low[a]) / cells[a];
  }
  // Node j (j = -1 .. cells) at the centre of cell j, stored at j + 1.
  const int across[3] = {cells[0] + 2, cells[1] + 2, cells[2] + 2};
  BsplineLattice lattice;
  for (int k = 0; k < across[2]; ++k)
    for (int j = 0; j < across[1]; ++j)
      for (int i = 0; i < across[0]; ++i)
        lattice.nodes_m.push_back(
            low + Eigen::Vector3d((i - 0.5) * step_m[0], (j - 0.5) * step_m[1], (k - 0.5) * step_m[2]));
  lattice.stride[0] = 1;
  lattice.stride[1] = static_cast<uint32_t>(across[0]);
  lattice.stride[2] = static_cast<uint32_t>(across[0] * across[1]);
  lattice.base.reserve(vertices_m.size());
  lattice.axis_weights.reserve(9 * vertices_m.size());
  for (const auto& v : vertices_m) {
    const Eigen::Vector3d t = (v.cast<double>() - low).cwiseQuotient(step_m);
    uint32_t base = 0;
    for (int a = 0; a < 3; ++a) {
      const int c = std::clamp(static_cast<int>(std::floor(t[a])), 0, cells[a] - 1);
      const double f = std::clamp(t[a] - c, 0.0, 1.0);
      base += static_cast<uint32_t>(c) * lattice.stride[a];  // node c - 1 is stored at c
      lattice.axis_weights.push_back(static_cast<float>(0.5 * (1 - f) * (1 - f)));
      lattice.axis_weights.push_back(static_cast<float>(0.5 + f * (1 - f)));
      lattice.axis_weights.push_back(static_cast<float>(0.5 * f * f));
    }
    lattice.base.push_back(base);
  }
  return lattice;
}

}  // namespace deform::detail
