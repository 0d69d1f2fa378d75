#include "nearest_points.hpp"

#include <algorithm>
#include <numeric>

namespace deform::detail {
namespace {
constexpr uint32_t kLeafSize = 8;
}

PointKdTree::PointKdTree(const std::vector<Eigen::Vector3d>& points)
    : points_(points), order_(points.size()) {
  std::iota(order_.begin(), order_.end(), 0u);
  nodes_.reserve(2 * points.size() / kLeafSize + 2);
  build(0, static_cast<uint32_t>(points.size()));
}

int32_t PointKdTree::build(uint32_t begin, uint32_t end) {
  const auto id = static_cast<int32_t>(nodes_.size());
  nodes_.push_back({begin, end, -1, -1, -1, 0});
  if (end - begin <= kLeafSize) return id;
  Eigen::Vector3d lo = points_[order_[begin]], hi = lo;
  for (uint32_t i = begin; i < end; ++i) {
    lo = lo.cwiseMin(points_[order_[i]]);
    hi = hi.cwiseMax(points_[order_[i]]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(
      order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](uint32_t a, uint32_t b) {
        return points_[a][axis] < points_[b][axis] || (points_[a][axis] == points_[b][axis] && a < b);
      });
  const double split = points_[order_[mid]][axis];
  const int32_t left = build(begin, mid);
  const int32_t right = build(mid, end);
  nodes_[static_cast<std::size_t>(id)].axis = axis;
  nodes_[static_cast<std::size_t>(id)].split = split;
  nodes_[static_cast<std::size_t>(id)].left = left;
  nodes_[static_cast<std::size_t>(id)].right = right;
  return id;
}

void PointKdTree::search(int32_t id, const Eigen::Vector3d& q, std::size_t k,
                         std::vector<RankedPoint>& heap) const {
  const Node& node = nodes_[static_cast<std::size_t>(id)];
  if (node.axis < 0) {
    for (uint32_t i = node.begin; i < node.end; ++i) {
      RankedPoint candidate{(points_[order_[i]] - q).squaredNorm(), order_[i]};
      if (heap.size() < k) {
        heap.push_back(candidate);
        std::push_heap(heap.begin(), heap.end());
      } else if (candidate < heap.front()) {
        std::pop_heap(heap.begin(), heap.end());
        heap.back() = candidate;
        std::push_heap(heap.begin(), heap.end());
      }
    }
    return;
  }
  const double offset = q[node.axis] - node.split;
  const int32_t near = offset < 0 ? node.left : node.right;
  const int32_t far = offset < 0 ? node.right : node.left;
  search(near, q, k, heap);
  // Points on the far side are at least |offset| away; equal distances must still be visited (ties).
  if (heap.size() < k || offset * offset <= heap.front().distance2_m2) search(far, q, k, heap);
}

void PointKdTree::nearest(const Eigen::Vector3d& query, std::size_t k, std::vector<RankedPoint>& heap) const {
  heap.clear();
  if (k == 0 || points_.empty()) return;
  search(0, query, k, heap);
  std::sort_heap(heap.begin(), heap.end());
}

}  // namespace deform::detail
