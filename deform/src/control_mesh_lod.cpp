// Level of detail of the control mesh: the convex hull reduced (meshoptimizer, then re-hulled) or
// refined (longest-edge bisection of its faces) to a target number of control points.
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>
#include <deform/vertex_grid.hpp>

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <string>
#include <tuple>

#include "sweep_order.hpp"

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

std::vector<uint32_t> farthestPoints(const std::vector<Eigen::Vector3d>& candidates, std::size_t count,
                                     const Eigen::Vector3d& centre, const std::vector<uint32_t>& mirror_of,
                                     const std::vector<char>& corner, double corner_spacing_m,
                                     bool by_cells) {
  const bool symmetric = !mirror_of.empty();
  std::vector<double> nearest_taken2(candidates.size(), std::numeric_limits<double>::infinity());
  // The farthest candidate of each kind (any, corners, on the plane, corners on the plane): heaps of
  // (squared distance to the nearest taken, index), the largest distance and then the lowest index on
  // top; an entry whose distance has since shrunk is dropped when it comes up.
  using Entry = std::pair<double, uint32_t>;
  const auto below = [](const Entry& a, const Entry& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
  };
  std::array<std::vector<Entry>, 4> heaps;
  const auto kinds = [&](uint32_t c) {
    return (corner[c] ? 1u : 0u) | (symmetric && mirror_of[c] == c ? 2u : 0u);
  };
  const auto push = [&](uint32_t c) {
    for (unsigned kind = 0; kind < 4; ++kind)
      if ((kinds(c) & kind) == kind) {
        heaps[kind].emplace_back(nearest_taken2[c], c);
        std::push_heap(heaps[kind].begin(), heaps[kind].end(), below);
      }
  };
  const auto top = [&](unsigned kind) {
    std::vector<Entry>& heap = heaps[kind];
    while (!heap.empty() && heap.front().first != nearest_taken2[heap.front().second]) {
      std::pop_heap(heap.begin(), heap.end(), below);
      heap.pop_back();
    }
    return heap.empty() ? Entry{-1.0, static_cast<uint32_t>(candidates.size())} : heap.front();
  };
  // Candidates by cell, so that a point taken updates only those nearer it than the largest gap (no
  // other can come nearer to it than to what was taken before): about linear in the points taken.
  const VertexGrid grid(candidates, 4);
  std::vector<uint32_t> near;
  std::vector<uint32_t> taken;
  auto take = [&](uint32_t i) {
    taken.push_back(i);
    const Eigen::Vector3d& p = candidates[i];
    if (taken.size() == 1 || !by_cells) {  // every candidate (the reference: at every point taken)
      for (uint32_t c = 0; c < candidates.size(); ++c) {
        const double d2 = (candidates[c] - p).squaredNorm();
        if (d2 < nearest_taken2[c]) {
          nearest_taken2[c] = d2;
          if (by_cells) push(c);
        }
      }
      return;
    }
    const double reach_m = std::sqrt(top(0).first) * (1 + 1e-9);
    near.clear();
    grid.query({(p.array() - reach_m).matrix(), (p.array() + reach_m).matrix()}, near);
    for (uint32_t c : near) {
      const double d2 = (candidates[c] - p).squaredNorm();
      if (d2 < nearest_taken2[c]) {
        nearest_taken2[c] = d2;
        push(c);
      }
    }
  };
  bool corners_only = true;
  bool first = true;
  while (taken.size() < count) {
    const bool need_single = symmetric && count - taken.size() == 1;
    auto pick = [&]() -> std::pair<std::size_t, double> {
      if (!first && by_cells) {
        const Entry best = top((corners_only ? 1u : 0u) | (need_single ? 2u : 0u));
        return {best.second, best.first};
      }
      std::size_t best = candidates.size();
      double best_score = -1;
      for (std::size_t c = 0; c < candidates.size(); ++c) {
        if (need_single && mirror_of[c] != c) continue;
        if (corners_only && !corner[c]) continue;
        const double score = first ? (candidates[c] - centre).squaredNorm() : nearest_taken2[c];
        if (score > best_score) best_score = score, best = c;
      }
      return {best, best_score};
    };
    auto [next, score] = pick();
    if (corners_only &&
        (next == candidates.size() || (!first && score < corner_spacing_m * corner_spacing_m))) {
      corners_only = false;
      std::tie(next, score) = pick();
    }
    first = false;
    if (next == candidates.size() || score <= 0) break;  // every distinct candidate is taken
    take(static_cast<uint32_t>(next));
    if (symmetric && mirror_of[next] != next && taken.size() < count) take(mirror_of[next]);
  }
  return taken;
}

namespace {

/// Mirror images within the set (y -> -y), or empty when some point has none. Points within `tol_m` of
/// the plane are their own images.
std::vector<uint32_t> mirrorPairs(const std::vector<Eigen::Vector3d>& points, double tol_m) {
  std::map<std::array<double, 3>, uint32_t> index;
  for (uint32_t i = 0; i < points.size(); ++i) index[{points[i].x(), points[i].y(), points[i].z()}] = i;
  std::vector<uint32_t> mirror(points.size());
  for (uint32_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (std::abs(p.y()) <= tol_m) {
      mirror[i] = i;
      continue;
    }
    auto it = index.find({p.x(), -p.y(), p.z()});
    if (it == index.end()) return {};
    mirror[i] = it->second;
  }
  return mirror;
}

/// Points spread over the surface by area: each triangle gets its share of `count` (the fractional
/// remainder carried to the next triangle, so the total is exact and nothing is random), placed by the
/// R2 low-discrepancy sequence folded into the triangle.
std::vector<Eigen::Vector3d> areaSamples(const ControlMesh& mesh, std::size_t count) {
  double total_area = 0;
  std::vector<double> area(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    area[t] = 0.5 * (mesh.points_m[tri[1]] - mesh.points_m[tri[0]])
                        .cross(mesh.points_m[tri[2]] - mesh.points_m[tri[0]])
                        .norm();
    total_area += area[t];
  }
  std::vector<Eigen::Vector3d> samples;
  samples.reserve(count + 1);
  const double g = 1.32471795724474602596;  // plastic number: R2 sequence (Roberts 2018)
  const double a1 = 1.0 / g, a2 = 1.0 / (g * g);
  double carried = 0;
  std::size_t sequence = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    carried += static_cast<double>(count) * area[t] / total_area;
    const auto here = static_cast<std::size_t>(carried);
    carried -= static_cast<double>(here);
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d a = mesh.points_m[tri[0]], ab = mesh.points_m[tri[1]] - a,
                          ac = mesh.points_m[tri[2]] - a;
    for (std::size_t k = 0; k < here; ++k, ++sequence) {
      double u = std::fmod(0.5 + a1 * static_cast<double>(sequence), 1.0);
      double v = std::fmod(0.5 + a2 * static_cast<double>(sequence), 1.0);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      samples.push_back(a + u * ab + v * ac);
    }
  }
  return samples;
}

/// Even spread: candidates are the hull's vertices (its corners) plus eight points per control point
/// spread over its surface by area, so large flat faces such as a floor pan are covered as densely as
/// the curved ones; farthest-point sampling then takes the control points.
///
/// A body whose hull is symmetric about the X-Z plane keeps that symmetry: candidates are taken on the
/// half y >= 0 and mirrored exactly, and points are chosen in mirror pairs.
ControlMesh evenControlMesh(const ControlMesh& hull, std::size_t target, const std::string& where) {
  std::vector<Eigen::Vector3d> candidates = hull.points_m;
  const auto samples = areaSamples(hull, 8 * target);
  candidates.insert(candidates.end(), samples.begin(), samples.end());
  std::vector<char> corner(candidates.size(), 0);
  std::fill(corner.begin(), corner.begin() + static_cast<std::ptrdiff_t>(hull.hull_vertex_count), 1);
  double area_m2 = 0;
  for (const auto& t : hull.triangles)
    area_m2 +=
        0.5 *
        (hull.points_m[t[1]] - hull.points_m[t[0]]).cross(hull.points_m[t[2]] - hull.points_m[t[0]]).norm();
  // Corners closer than half the even spacing would crowd a coarse mesh; past that, evenness wins.
  const double corner_spacing_m = 0.5 * std::sqrt(area_m2 / static_cast<double>(target));
  double extent = 0;
  for (const auto& p : hull.points_m) extent = std::max(extent, (p - hull.centre_of_mass_m).norm());
  const double plane_tol_m = 1e-9 * extent;
  std::vector<uint32_t> mirror;
  if (!mirrorPairs(hull.points_m, plane_tol_m).empty()) {
    std::vector<Eigen::Vector3d> half;
    std::vector<char> half_corner;
    // A pair closer to the plane than a quarter of the spacing would sit crowded across it: such a
    // candidate is moved onto the plane instead (a change of position well under the spacing).
    const double onto_plane_m = std::max(plane_tol_m, 0.5 * corner_spacing_m);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const auto& c = candidates[i];
      if (c.y() > onto_plane_m) {
        half.push_back(c);
        half.emplace_back(c.x(), -c.y(), c.z());
        half_corner.insert(half_corner.end(), 2, corner[i]);
      } else if (c.y() >= -onto_plane_m) {
        half.emplace_back(c.x(), 0.0, c.z());
        half_corner.push_back(corner[i]);
      }
    }
    candidates = std::move(half);
    corner = std::move(half_corner);
    mirror = mirrorPairs(candidates, plane_tol_m);
  }
  const auto taken =
      farthestPoints(candidates, target, hull.centre_of_mass_m, mirror, corner, corner_spacing_m, true);
  std::vector<Eigen::Vector3d> chosen;
  for (uint32_t i : taken) chosen.push_back(candidates[i]);
  ControlMesh mesh = triangulateOnConvexSurface(chosen, where.c_str());
  if (!mirror.empty()) mesh.mirror_of = mirrorPairs(mesh.points_m, plane_tol_m);
  return mesh;
}

}  // namespace

LodMethod parseLodMethod(const std::string& text, const std::string& field) {
  if (text == "even") return LodMethod::Even;
  if (text == "simplify") return LodMethod::Simplify;
  throw InputError(field + ": '" + text + "' is not a level-of-detail method (even, simplify)");
}

namespace {

/// Numbers the control points in order along the longest side of their bounding box (ties by the old
/// number): the body's two halves across that side (the sweep's, deform/src/sweep_order.hpp) are then
/// the first and the second half of the arrays, so two threads sweeping them write to different cache
/// lines (numbered as they were chosen, the halves' points alternated in memory: 1.05x on two threads
/// against 1.15x).
void numberAlongLongestSide(ControlMesh& mesh) {
  const std::size_t n = mesh.points_m.size();
  const std::vector<uint32_t> old_of = orderAlongLongestSide(mesh.points_m);
  std::vector<uint32_t> new_of(n);
  for (uint32_t k = 0; k < n; ++k) new_of[old_of[k]] = k;
  std::vector<Eigen::Vector3d> points(n);
  for (uint32_t k = 0; k < n; ++k) points[k] = mesh.points_m[old_of[k]];
  mesh.points_m = std::move(points);
  for (auto& t : mesh.triangles)
    for (uint32_t& corner : t) corner = new_of[corner];
  if (!mesh.mirror_of.empty()) {
    std::vector<uint32_t> mirror(n);
    for (uint32_t k = 0; k < n; ++k) mirror[k] = new_of[mesh.mirror_of[old_of[k]]];
    mesh.mirror_of = std::move(mirror);
  }
  // The edges keep their order, which is not along the body: a Gauss-Seidel sweep along it carried a
  // push at the front through the whole body in one sweep (a pole 15 cm into the front moved the rear
  // half 10 mm, against 5 mm in this order).
  for (ControlEdge& e : mesh.edges) {
    e.a = new_of[e.a];
    e.b = new_of[e.b];
    e.left = new_of[e.left];
    e.right = new_of[e.right];
  }
}

}  // namespace

ControlMesh buildControlMesh(const std::vector<Eigen::Vector3d>& points, std::size_t target_points,
                             const char* source, LodMethod method) {
  const std::string where = source ? source : "mesh";
  if (target_points < kMinControlPoints || target_points > kMaxControlPoints)
    throw InputError(where + ": control points must be between " + std::to_string(kMinControlPoints) +
                     " and " + std::to_string(kMaxControlPoints) + " (got " + std::to_string(target_points) +
                     ")");
  ControlMesh hull = convexHull(points, where.c_str());
  const std::size_t hull_vertices = hull.hull_vertex_count;
  ControlMesh mesh;
  if (hull.points_m.size() == target_points) {
    mesh = hull;  // the hull itself, with its symmetric facet fans
  } else if (method == LodMethod::Even) {
    mesh = evenControlMesh(hull, target_points, where);
  } else if (hull.points_m.size() > target_points) {
    mesh = reduceHull(hull, target_points, where);
  } else {
    mesh = hull;
    refineHull(mesh, target_points);
    finishControlMesh(mesh);
  }
  numberAlongLongestSide(mesh);
  mesh.hull_vertex_count = hull_vertices;
  // The body's centre of mass is the full hull's, whatever the level of detail, as long as the control
  // surface encloses it (every tetrahedron of the fan positive); a very coarse mesh keeps its own.
  bool encloses = true;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.points_m[t[0]] - hull.centre_of_mass_m,
                          b = mesh.points_m[t[1]] - hull.centre_of_mass_m,
                          c = mesh.points_m[t[2]] - hull.centre_of_mass_m;
    encloses = encloses && a.dot(b.cross(c)) > 0;
  }
  if (encloses) mesh.centre_of_mass_m = hull.centre_of_mass_m;
  return mesh;
}

}  // namespace deform
