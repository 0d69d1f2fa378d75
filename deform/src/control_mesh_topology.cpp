// Edges, volume and centre of mass of a closed control surface.
#include <deform/control_mesh.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>

#include "nearest_points.hpp"
#include "triangle_distance.hpp"

namespace deform {

void finishControlMesh(ControlMesh& mesh) {
  // Directed half-edge a->b belongs to the triangle whose third vertex is `opposite`.
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> opposite;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      opposite[{a, b}] = t[static_cast<std::size_t>((k + 2) % 3)];
    }
  }
  mesh.edges.clear();
  for (const auto& [ab, left] : opposite) {
    auto [a, b] = ab;
    if (a > b) continue;  // each edge once, from its lower index
    auto twin = opposite.find({b, a});
    assert(twin != opposite.end() && "control surface must be closed");
    mesh.edges.push_back({a, b, left, twin == opposite.end() ? left : twin->second});
  }

  // Volume and centroid of the solid by a fan of tetrahedra from a reference point (divergence
  // theorem). The reference is the mean point, so a car far from the origin loses no precision.
  Eigen::Vector3d ref = Eigen::Vector3d::Zero();
  for (const auto& p : mesh.points_m) ref += p;
  if (!mesh.points_m.empty()) ref /= static_cast<double>(mesh.points_m.size());
  double volume = 0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.points_m[t[0]] - ref, b = mesh.points_m[t[1]] - ref,
                          c = mesh.points_m[t[2]] - ref;
    double v = a.dot(b.cross(c)) / 6.0;
    volume += v;
    moment += v * (a + b + c) / 4.0;
  }
  mesh.volume_m3 = volume;
  mesh.centre_of_mass_m = volume > 0 ? Eigen::Vector3d(ref + moment / volume) : ref;
}

double enclosedVolume_m3(const std::vector<Eigen::Vector3d>& points_m,
                         const std::vector<std::array<uint32_t, 3>>& triangles) {
  Eigen::Vector3d ref = Eigen::Vector3d::Zero();
  for (const auto& p : points_m) ref += p;
  if (!points_m.empty()) ref /= static_cast<double>(points_m.size());
  double volume = 0;
  for (const auto& t : triangles)
    volume += (points_m[t[0]] - ref).dot((points_m[t[1]] - ref).cross(points_m[t[2]] - ref)) / 6.0;
  return volume;
}

ControlMeshStats controlMeshStats(const ControlMesh& mesh) {
  ControlMeshStats stats;
  stats.shortest_edge_m = mesh.edges.empty() ? 0 : std::numeric_limits<double>::infinity();
  for (const auto& e : mesh.edges) {
    double length = (mesh.points_m[e.a] - mesh.points_m[e.b]).norm();
    stats.longest_edge_m = std::max(stats.longest_edge_m, length);
    stats.shortest_edge_m = std::min(stats.shortest_edge_m, length);
  }
  // The largest hole: sample every triangle (its corners, edge midpoints and a 6 x 6 barycentric grid)
  // and take the largest distance to the nearest control point.
  if (mesh.points_m.empty()) return stats;
  detail::PointKdTree tree(mesh.points_m);
  std::vector<detail::RankedPoint> nearest;
  constexpr int kGrid = 6;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.points_m[t[0]], b = mesh.points_m[t[1]], c = mesh.points_m[t[2]];
    stats.surface_area_m2 += 0.5 * (b - a).cross(c - a).norm();
    for (int i = 0; i <= kGrid; ++i) {
      for (int j = 0; i + j <= kGrid; ++j) {
        const double u = double(i) / kGrid, v = double(j) / kGrid;
        tree.nearest(a + u * (b - a) + v * (c - a), 1, nearest);
        stats.largest_gap_m = std::max(stats.largest_gap_m, std::sqrt(nearest[0].distance2_m2));
      }
    }
  }
  return stats;
}

double controlSurfaceShortfall_m(const ControlMesh& mesh, const std::vector<Eigen::Vector3d>& points) {
  double shortfall_m = 0;
  for (const Eigen::Vector3d& p : points) {
    // Inside a closed convex surface every face plane has the point behind it; outside, the distance is
    // to the nearest triangle.
    bool outside = false;
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.points_m[t[0]], b = mesh.points_m[t[1]], c = mesh.points_m[t[2]];
      if ((b - a).cross(c - a).dot(p - a) > 0) {
        outside = true;
        break;
      }
    }
    if (!outside) continue;
    double nearest2 = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d a = mesh.points_m[t[0]], b = mesh.points_m[t[1]], c = mesh.points_m[t[2]];
      const Eigen::Vector3d w = detail::nearestOnTriangle(p, a, b, c);  // barycentric
      nearest2 = std::min(nearest2, (p - (w[0] * a + w[1] * b + w[2] * c)).squaredNorm());
    }
    shortfall_m = std::max(shortfall_m, std::sqrt(nearest2));
  }
  return shortfall_m;
}

std::vector<uint32_t> triangleNeighbours(const std::vector<std::array<uint32_t, 3>>& triangles) {
  std::vector<std::pair<uint64_t, uint32_t>> edges;  // (undirected edge key, 3 t + j)
  for (uint32_t t = 0; t < triangles.size(); ++t)
    for (uint32_t j = 0; j < 3; ++j) {
      const uint32_t u = triangles[t][j], v = triangles[t][(j + 1) % 3];
      edges.emplace_back((static_cast<uint64_t>(std::min(u, v)) << 32) | std::max(u, v), 3 * t + j);
    }
  std::sort(edges.begin(), edges.end());
  std::vector<uint32_t> across(3 * triangles.size(), UINT32_MAX);
  for (std::size_t k = 0; k + 1 < edges.size(); ++k)
    if (edges[k].first == edges[k + 1].first) {
      across[edges[k].second] = edges[k + 1].second / 3;
      across[edges[k + 1].second] = edges[k].second / 3;
    }
  return across;
}

}  // namespace deform
