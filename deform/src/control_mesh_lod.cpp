// Level of detail of the control mesh: the convex hull reduced (meshoptimizer, then re-hulled) or
// refined (longest-edge bisection of its faces) to a target number of control points.
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>

#include <meshoptimizer.h>

#include <cmath>
#include <map>
#include <queue>
#include <string>
#include <tuple>

namespace deform {
namespace {

constexpr std::size_t kMinControlPoints = 4;
constexpr std::size_t kMaxControlPoints = 100000;

/// Hull vertices kept by meshoptimizer's simplifier for a target triangle count.
std::vector<Eigen::Vector3d> simplifiedVertices(const ControlMesh& hull, std::size_t target_triangles,
                                                bool sloppy) {
  // meshoptimizer works in float; positions relative to the centre keep their precision.
  const Eigen::Vector3d centre = hull.centre_of_mass_m;
  std::vector<float> xyz(hull.points_m.size() * 3);
  for (std::size_t i = 0; i < hull.points_m.size(); ++i)
    for (int a = 0; a < 3; ++a)
      xyz[3 * i + static_cast<std::size_t>(a)] = static_cast<float>(hull.points_m[i][a] - centre[a]);
  std::vector<unsigned> indices;
  for (const auto& t : hull.triangles) indices.insert(indices.end(), t.begin(), t.end());
  std::vector<unsigned> out(indices.size());
  const float no_error_limit = 1e30f;  // the target count decides, not the error
  std::size_t count =
      sloppy ? meshopt_simplifySloppy(out.data(), indices.data(), indices.size(), xyz.data(),
                                      hull.points_m.size(), 3 * sizeof(float), 3 * target_triangles,
                                      no_error_limit, nullptr)
             : meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(), hull.points_m.size(),
                                3 * sizeof(float), 3 * target_triangles, no_error_limit, 0, nullptr);
  std::vector<char> used(hull.points_m.size(), 0);
  for (std::size_t i = 0; i < count; ++i) used[out[i]] = 1;
  std::vector<Eigen::Vector3d> kept;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) kept.push_back(hull.points_m[i]);
  return kept;
}

/// Fewer points: simplify the hull's surface, then take the convex hull of what is left so the control
/// mesh stays convex and closed. The simplifier's target is steered until the count is within 5 %.
ControlMesh reduceHull(const ControlMesh& hull, std::size_t target, const std::string& where) {
  // A closed triangulated sphere has 2V - 4 triangles (Euler: V - E + F = 2).
  double request = static_cast<double>(target);
  ControlMesh best = hull;
  std::size_t best_error = hull.points_m.size() - target;
  for (int attempt = 0; attempt < 12 && best_error > target / 20; ++attempt) {
    auto target_triangles = static_cast<std::size_t>(std::max(4.0, 2.0 * std::round(request) - 4.0));
    auto kept = simplifiedVertices(hull, target_triangles, false);
    if (kept.size() > target + target / 20) kept = simplifiedVertices(hull, target_triangles, true);
    if (kept.size() < 4) {
      request *= 1.2;
      continue;
    }
    // Diagonals, not centroid fans: new points would defeat the count (the simplifier breaks exact
    // symmetry anyway).
    ControlMesh candidate = convexHull(kept, where.c_str(), FacetSplit::Diagonals);
    std::size_t n = candidate.points_m.size();
    std::size_t error = n > target ? n - target : target - n;
    if (error < best_error) {
      best_error = error;
      best = std::move(candidate);
    }
    request *= static_cast<double>(target) / static_cast<double>(std::max<std::size_t>(n, 1));
  }
  return best;
}

/// More points: split the longest edge of the surface (and both triangles beside it) at its midpoint
/// until the target count is reached. Every new point lies on the hull; spacing evens out because the
/// longest gap is always the one closed next. Ties go to the lower vertex indices (deterministic).
void refineHull(ControlMesh& mesh, std::size_t target) {
  using Key = std::pair<uint32_t, uint32_t>;
  auto key = [](uint32_t a, uint32_t b) { return a < b ? Key{a, b} : Key{b, a}; };
  // Undirected edge -> the triangles on either side.
  std::map<Key, std::array<uint32_t, 2>> sides;
  auto addSide = [&](uint32_t a, uint32_t b, uint32_t tri) {
    auto [it, fresh] = sides.try_emplace(key(a, b), std::array<uint32_t, 2>{tri, tri});
    if (!fresh) it->second[1] = tri;
  };
  auto replaceSide = [&](uint32_t a, uint32_t b, uint32_t from, uint32_t to) {
    auto& s = sides.at(key(a, b));
    (s[0] == from ? s[0] : s[1]) = to;
  };
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      addSide(mesh.triangles[t][static_cast<std::size_t>(k)],
              mesh.triangles[t][static_cast<std::size_t>((k + 1) % 3)], t);

  using Entry = std::tuple<double, uint32_t, uint32_t>;  // length, then indices reversed for ties
  auto cmp = [](const Entry& x, const Entry& y) {
    if (std::get<0>(x) != std::get<0>(y)) return std::get<0>(x) < std::get<0>(y);
    return std::make_pair(std::get<1>(x), std::get<2>(x)) > std::make_pair(std::get<1>(y), std::get<2>(y));
  };
  std::priority_queue<Entry, std::vector<Entry>, decltype(cmp)> longest(cmp);
  auto push = [&](uint32_t a, uint32_t b) {
    Key k = key(a, b);
    longest.emplace((mesh.points_m[a] - mesh.points_m[b]).squaredNorm(), k.first, k.second);
  };
  for (const auto& [k, s] : sides) push(k.first, k.second);

  while (mesh.points_m.size() < target && !longest.empty()) {
    auto [length2, a, b] = longest.top();
    longest.pop();
    auto it = sides.find({a, b});
    if (it == sides.end()) continue;  // already split
    const auto tris = it->second;
    sides.erase(it);
    const auto m = static_cast<uint32_t>(mesh.points_m.size());
    mesh.points_m.push_back(0.5 * (mesh.points_m[a] + mesh.points_m[b]));
    for (uint32_t t : tris) {
      // Rotate so the triangle reads (p, q, r) with p-q the split edge in its own winding.
      auto tri = mesh.triangles[t];
      while (!((tri[0] == a && tri[1] == b) || (tri[0] == b && tri[1] == a)))
        std::rotate(tri.begin(), tri.begin() + 1, tri.end());
      const uint32_t p = tri[0], q = tri[1], r = tri[2];
      const auto fresh = static_cast<uint32_t>(mesh.triangles.size());
      mesh.triangles[t] = {p, m, r};
      mesh.triangles.push_back({m, q, r});
      replaceSide(q, r, t, fresh);
      addSide(p, m, t);
      addSide(m, q, fresh);
      addSide(m, r, t);
      addSide(m, r, fresh);
      push(p, m);
      push(m, q);
      push(m, r);
    }
  }
}

}  // namespace

ControlMesh buildControlMesh(const std::vector<Eigen::Vector3d>& points, std::size_t target_points,
                             const char* source) {
  const std::string where = source ? source : "mesh";
  if (target_points < kMinControlPoints || target_points > kMaxControlPoints)
    throw InputError(where + ": control points must be between " + std::to_string(kMinControlPoints) +
                     " and " + std::to_string(kMaxControlPoints) + " (got " + std::to_string(target_points) +
                     ")");
  ControlMesh hull = convexHull(points, where.c_str());
  const std::size_t hull_vertices = hull.points_m.size();
  ControlMesh mesh;
  if (hull_vertices > target_points) {
    mesh = reduceHull(hull, target_points, where);
  } else {
    mesh = std::move(hull);
    refineHull(mesh, target_points);
    finishControlMesh(mesh);
  }
  mesh.hull_vertex_count = hull_vertices;
  return mesh;
}

}  // namespace deform
