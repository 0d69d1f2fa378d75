// The red-green hierarchy of a control surface (refinement.hpp).
#include <deform/error.hpp>
#include <deform/refinement.hpp>

#include <stdexcept>
#include <string>

namespace deform {
namespace {

uint64_t directed(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(a) << 32) | b;
}

uint64_t undirected(uint32_t a, uint32_t b) {
  return a < b ? directed(a, b) : directed(b, a);
}

}  // namespace

SurfaceHierarchy::SurfaceHierarchy(const ControlMesh& base)
    : rest_points_m_(base.points_m), base_points_(base.points_m.size()) {
  for (const auto& t : base.triangles) {
    for (uint32_t c : t)
      if (c >= base_points_) throw InputError("control mesh: triangle index out of range");
    Node node;
    node.corners = t;
    const auto id = static_cast<uint32_t>(nodes_.size());
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      if (!edge_owner_.emplace(directed(a, b), id).second)
        throw InputError("control mesh: edge " + std::to_string(a) + "-" + std::to_string(b) +
                         " is in two triangles of the same direction (not an oriented 2-manifold)");
    }
    nodes_.push_back(node);
  }
  for (const auto& [key, node] : edge_owner_)
    if (!edge_owner_.count((key << 32) | (key >> 32)))
      throw InputError("control mesh: edge " + std::to_string(key >> 32) + "-" +
                       std::to_string(key & 0xffffffffu) + " is open (the surface must be closed)");
}

uint32_t SurfaceHierarchy::midpoint(uint32_t a, uint32_t b) const {
  const auto it = edge_midpoint_.find(undirected(a, b));
  return it == edge_midpoint_.end() ? kNoIndex : it->second;
}

uint32_t SurfaceHierarchy::ownerOf(uint32_t a, uint32_t b) const {
  const auto it = edge_owner_.find(directed(a, b));
  return it == edge_owner_.end() ? kNoIndex : it->second;
}

uint32_t SurfaceHierarchy::addMidpoint(uint32_t a, uint32_t b) {
  const uint32_t existing = midpoint(a, b);
  if (existing != kNoIndex) return existing;
  const auto p = static_cast<uint32_t>(rest_points_m_.size());
  rest_points_m_.push_back(0.5 * (rest_points_m_[a] + rest_points_m_[b]));
  parents_.push_back({a, b});
  edge_midpoint_.emplace(undirected(a, b), p);
  return p;
}

uint32_t SurfaceHierarchy::across(uint32_t node, int k) const {
  const Node& t = nodes_[node];
  const uint32_t a = t.corners[static_cast<std::size_t>(k)],
                 b = t.corners[static_cast<std::size_t>((k + 1) % 3)];
  const uint32_t same = ownerOf(b, a);
  if (same != kNoIndex) return same;
  // The other side is a level coarser: this edge is half of an edge of the parent.
  const Node& parent = nodes_[t.parent];
  for (int j = 0; j < 3; ++j) {
    const uint32_t x = parent.corners[static_cast<std::size_t>(j)];
    const uint32_t y = parent.corners[static_cast<std::size_t>((j + 1) % 3)];
    const uint32_t m = midpoint(x, y);
    if ((a == x && b == m) || (a == m && b == y)) return ownerOf(y, x);
  }
  throw std::logic_error("surface hierarchy: an edge with no neighbour");
}

bool SurfaceHierarchy::split(uint32_t node, std::size_t max_points) {
  if (node >= nodes_.size() || !isLeaf(node)) return false;
  const Mark start = mark();
  const std::size_t splits = split_order_.size();
  if (splitGraded(node, max_points) && rest_points_m_.size() <= max_points) return true;
  // A refinement that would pass the bound is undone whole, the grading and closure it started too: the
  // nodes, points and edges it added go, and the nodes it split are leaves again.
  for (std::size_t id = start.nodes; id < nodes_.size(); ++id) {
    const auto& t = nodes_[id].corners;
    for (int k = 0; k < 3; ++k)
      edge_owner_.erase(directed(t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]));
  }
  for (std::size_t k = start.points; k < rest_points_m_.size(); ++k) {
    const auto [a, b] = parents_[k - base_points_];
    edge_midpoint_.erase(undirected(a, b));
  }
  for (std::size_t i = splits; i < split_order_.size(); ++i) nodes_[split_order_[i]].first_child = kNoIndex;
  nodes_.resize(start.nodes);
  rest_points_m_.resize(start.points);
  parents_.resize(start.points - base_points_);
  split_order_.resize(splits);
  return false;
}

bool SurfaceHierarchy::splitGraded(uint32_t node, std::size_t max_points) {
  if (!isLeaf(node)) return true;
  if (rest_points_m_.size() > max_points) return false;
  // Grading: a coarser neighbour splits first, so neighbours never differ by more than one level.
  for (int k = 0; k < 3; ++k) {
    const uint32_t other = across(node, k);
    if (nodes_[other].level < nodes_[node].level && !splitGraded(other, max_points)) return false;
  }
  const std::array<uint32_t, 3> c = nodes_[node].corners;
  const uint32_t m01 = addMidpoint(c[0], c[1]), m12 = addMidpoint(c[1], c[2]), m20 = addMidpoint(c[2], c[0]);
  const auto first = static_cast<uint32_t>(nodes_.size());
  const uint32_t level = nodes_[node].level + 1;
  const std::array<std::array<uint32_t, 3>, 4> children = {
      {{c[0], m01, m20}, {m01, c[1], m12}, {m20, m12, c[2]}, {m01, m12, m20}}};
  for (std::size_t i = 0; i < 4; ++i) {
    const auto id = static_cast<uint32_t>(first + i);
    const auto& t = children[i];
    for (int k = 0; k < 3; ++k)
      edge_owner_[directed(t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)])] = id;
    nodes_.push_back({t, node, kNoIndex, level});
  }
  nodes_[node].first_child = first;
  split_order_.push_back(node);
  // Closure: a neighbour of this level left with two or three split edges splits too.
  for (int k = 0; k < 3; ++k) {
    const uint32_t other = ownerOf(c[static_cast<std::size_t>((k + 1) % 3)], c[static_cast<std::size_t>(k)]);
    if (other == kNoIndex || !isLeaf(other)) continue;
    int split_edges = 0;
    const auto& o = nodes_[other].corners;
    for (int j = 0; j < 3; ++j)
      split_edges +=
          midpoint(o[static_cast<std::size_t>(j)], o[static_cast<std::size_t>((j + 1) % 3)]) != kNoIndex;
    if (split_edges >= 2 && !splitGraded(other, max_points)) return false;
  }
  return true;
}

std::vector<std::array<uint32_t, 3>> SurfaceHierarchy::triangles(std::vector<uint32_t>* leaf_of) const {
  return triangles(mark(), leaf_of);
}

std::vector<std::array<uint32_t, 3>> SurfaceHierarchy::triangles(Mark then,
                                                                 std::vector<uint32_t>* leaf_of) const {
  std::vector<std::array<uint32_t, 3>> out;
  if (leaf_of) leaf_of->clear();
  auto emit = [&](const std::array<uint32_t, 3>& t, uint32_t leaf) {
    out.push_back(t);
    if (leaf_of) leaf_of->push_back(leaf);
  };
  for (uint32_t id = 0; id < then.nodes; ++id) {
    const Node& t = nodes_[id];
    if (t.first_child < then.nodes) continue;  // split by then
    int split_edge = -1;
    uint32_t m = kNoIndex;
    for (int k = 0; k < 3; ++k) {
      const uint32_t mid =
          midpoint(t.corners[static_cast<std::size_t>(k)], t.corners[static_cast<std::size_t>((k + 1) % 3)]);
      if (mid == kNoIndex || mid >= then.points) continue;
      if (split_edge >= 0) throw std::logic_error("surface hierarchy: a leaf with two split edges");
      split_edge = k;
      m = mid;
    }
    if (split_edge < 0) {
      emit(t.corners, id);
      continue;
    }
    const uint32_t x = t.corners[static_cast<std::size_t>(split_edge)];
    const uint32_t y = t.corners[static_cast<std::size_t>((split_edge + 1) % 3)];
    const uint32_t z = t.corners[static_cast<std::size_t>((split_edge + 2) % 3)];
    emit({x, m, z}, id);
    emit({m, y, z}, id);
  }
  return out;
}

}  // namespace deform
