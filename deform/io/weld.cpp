// Welding identical positions: separate parts, UV seams and flat-shading copies share vertices after it.
#include <deform/mesh_import.hpp>

#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace deform {
namespace {

/// Bit pattern of a position, with -0 and +0 made equal (they are the same point).
struct PositionKey {
  std::uint32_t bits[3];
  bool operator==(const PositionKey& other) const {
    return bits[0] == other.bits[0] && bits[1] == other.bits[1] && bits[2] == other.bits[2];
  }
};

PositionKey keyOf(const Eigen::Vector3f& p) {
  PositionKey key{};
  for (int i = 0; i < 3; ++i) {
    const float value = p[i] + 0.0f;  // -0 + 0 = +0
    std::memcpy(&key.bits[i], &value, sizeof value);
  }
  return key;
}

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& key) const {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the three words
    for (std::uint32_t word : key.bits) {
      h ^= word;
      h *= 1099511628211ull;
    }
    return static_cast<std::size_t>(h);
  }
};

}  // namespace

WeldResult weldPositions(Mesh& mesh) {
  WeldResult result;
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> first_index;
  first_index.reserve(mesh.positions_m.size());
  std::vector<std::uint32_t> remap(mesh.positions_m.size());
  std::vector<Eigen::Vector3f> welded;
  welded.reserve(mesh.positions_m.size());
  for (std::size_t i = 0; i < mesh.positions_m.size(); ++i) {
    const auto [it, inserted] =
        first_index.try_emplace(keyOf(mesh.positions_m[i]), static_cast<std::uint32_t>(welded.size()));
    if (inserted) welded.push_back(mesh.positions_m[i]);
    remap[i] = it->second;
  }
  result.merged_vertices = mesh.positions_m.size() - welded.size();

  std::vector<Triangle> kept;
  kept.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) {
    const Triangle w{remap[t[0]], remap[t[1]], remap[t[2]]};
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) {
      ++result.degenerate_triangles;
      continue;
    }
    kept.push_back(w);
  }
  // A vertex used only by dropped triangles would be a loose point (it would still shape the hull): drop it.
  std::vector<std::uint32_t> compact(welded.size(), UINT32_MAX);
  std::vector<Eigen::Vector3f> used;
  used.reserve(welded.size());
  for (Triangle& t : kept) {
    for (std::uint32_t& v : t) {
      if (compact[v] == UINT32_MAX) {
        compact[v] = static_cast<std::uint32_t>(used.size());
        used.push_back(welded[v]);
      }
      v = compact[v];
    }
  }
  result.unused_vertices = welded.size() - used.size();
  mesh.positions_m = std::move(used);
  mesh.triangles = std::move(kept);
  mesh.normals.clear();
  return result;
}

}  // namespace deform
