#pragma once
// K nearest control points of a vertex: a small kd-tree over the control points, so that building the
// skin costs O(V log N) instead of O(V N). Results equal the brute-force choice exactly: points are
// ranked by (squared distance, index), ties included.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace deform::detail {

struct RankedPoint {
  double distance2_m2;
  uint32_t index;
  bool operator<(const RankedPoint& o) const {
    return distance2_m2 < o.distance2_m2 || (distance2_m2 == o.distance2_m2 && index < o.index);
  }
};

class PointKdTree {
 public:
  explicit PointKdTree(const std::vector<Eigen::Vector3d>& points);
  /// The k nearest points to `query`, nearest first. `heap` is scratch space reused between calls.
  void nearest(const Eigen::Vector3d& query, std::size_t k, std::vector<RankedPoint>& heap) const;

 private:
  struct Node {
    uint32_t begin = 0, end = 0;  ///< range in order_ (leaves)
    int32_t left = -1, right = -1;
    int axis = -1;  ///< -1 for a leaf
    double split = 0;
  };
  int32_t build(uint32_t begin, uint32_t end);
  void search(int32_t node, const Eigen::Vector3d& q, std::size_t k, std::vector<RankedPoint>& heap) const;

  const std::vector<Eigen::Vector3d>& points_;
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace deform::detail
