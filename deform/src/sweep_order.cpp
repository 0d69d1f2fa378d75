#include "sweep_order.hpp"

#include <algorithm>
#include <numeric>

namespace deform {
namespace {

/// Appends `part` (pair indices) to `order`, window by window, each window by colour.
void appendWindowed(const std::vector<std::array<uint32_t, 2>>& pairs, const std::vector<uint32_t>& part,
                    std::size_t window, std::vector<uint64_t>& taken_by, std::vector<uint32_t>& order) {
  std::vector<std::pair<uint32_t, uint32_t>> coloured;  // (colour, pair)
  for (std::size_t begin = 0; begin < part.size(); begin += window) {
    const std::size_t end = std::min(part.size(), begin + window);
    coloured.clear();
    for (std::size_t j = begin; j < end; ++j) {
      const auto& [a, b] = pairs[part[j]];
      // A window of at most 64 pairs leaves each at most 63 others to conflict with: a free colour below 64.
      const uint64_t taken = taken_by[a] | taken_by[b];
      const auto colour = static_cast<uint32_t>(__builtin_ctzll(~taken));
      taken_by[a] |= uint64_t{1} << colour;
      taken_by[b] |= uint64_t{1} << colour;
      coloured.push_back({colour, part[j]});
    }
    for (std::size_t j = begin; j < end; ++j) taken_by[pairs[part[j]][0]] = taken_by[pairs[part[j]][1]] = 0;
    std::stable_sort(coloured.begin(), coloured.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& entry : coloured) order.push_back(entry.second);
  }
}

/// Re-sorts order[begin ..) by dependency level, stably (sweepOrder's by_level). `level_of_point` is all
/// zero on entry and on return.
void byLevel(const std::vector<std::array<uint32_t, 2>>& pairs, std::size_t begin,
             std::vector<uint32_t>& order, std::vector<uint32_t>& level_of_point) {
  std::vector<std::pair<uint32_t, uint32_t>> levelled;  // (level, pair)
  for (std::size_t j = begin; j < order.size(); ++j) {
    const auto& [a, b] = pairs[order[j]];
    const uint32_t level = std::max(level_of_point[a], level_of_point[b]);
    level_of_point[a] = level_of_point[b] = level + 1;
    levelled.push_back({level, order[j]});
  }
  for (std::size_t j = begin; j < order.size(); ++j)
    level_of_point[pairs[order[j]][0]] = level_of_point[pairs[order[j]][1]] = 0;
  std::stable_sort(levelled.begin(), levelled.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  for (std::size_t j = begin; j < order.size(); ++j) order[j] = levelled[j - begin].second;
}

}  // namespace

std::vector<uint32_t> orderAlongLongestSide(const std::vector<Eigen::Vector3d>& points_m) {
  std::vector<uint32_t> order(points_m.size());
  std::iota(order.begin(), order.end(), 0u);
  if (points_m.empty()) return order;
  Eigen::Vector3d low = points_m[0], high = points_m[0];
  for (const auto& p : points_m) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  Eigen::Index axis = 0;
  (high - low).maxCoeff(&axis);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t i, uint32_t j) { return points_m[i][axis] < points_m[j][axis]; });
  return order;
}

std::vector<uint8_t> bodyHalves(const std::vector<Eigen::Vector3d>& points_m) {
  std::vector<uint8_t> halves(points_m.size(), 0);
  const std::vector<uint32_t> order = orderAlongLongestSide(points_m);
  for (std::size_t k = points_m.size() / 2; k < points_m.size(); ++k) halves[order[k]] = 1;
  return halves;
}

SweepOrder sweepOrder(const std::vector<std::array<uint32_t, 2>>& pairs, const std::vector<uint8_t>& halves,
                      std::size_t window, bool by_level) {
  window = std::clamp<std::size_t>(window, 1, 64);
  std::vector<uint32_t> parts[3];  // half 0, half 1, across
  for (uint32_t k = 0; k < pairs.size(); ++k) {
    const uint8_t a = halves[pairs[k][0]], b = halves[pairs[k][1]];
    parts[a == b ? a : 2].push_back(k);
  }
  SweepOrder out;
  out.order.reserve(pairs.size());
  std::vector<uint64_t> taken_by(halves.size(), 0);
  std::vector<uint32_t> level_of_point(halves.size(), 0);
  for (int part = 0; part < 3; ++part) {
    const std::size_t begin = out.order.size();
    appendWindowed(pairs, parts[part], window, taken_by, out.order);
    if (by_level) byLevel(pairs, begin, out.order, level_of_point);
    if (part < 2) out.half_end[static_cast<std::size_t>(part)] = static_cast<uint32_t>(out.order.size());
  }
  return out;
}

}  // namespace deform
