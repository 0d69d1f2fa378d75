// The permanent-crush measurement of crash tests (simulation.hpp, crushProfile): the struck end's
// profile at equally spaced stations across the width, rest shape against the shape now. As in the
// NCAP / FMVSS 208 post-test vehicle measurements (NHTSA, "Laboratory Test Procedure for New Car
// Assessment Program Frontal Impact Testing", crush profile C1..C6 at six equally spaced stations).
#include <vehicle/simulation.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace vehicle {
namespace {

/// Furthest intersection along `d` of the line base + s d with the triangles (Moeller and Trumbore
/// 1997, "Fast, Minimum Storage Ray/Triangle Intersection"); none when the line misses them all.
std::optional<double> furthestHit(const std::vector<std::array<uint32_t, 3>>& triangles,
                                  const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& base,
                                  const Eigen::Vector3d& d) {
  std::optional<double> best;
  for (const auto& t : triangles) {
    const Eigen::Vector3d& p0 = points[t[0]];
    const Eigen::Vector3d e1 = points[t[1]] - p0, e2 = points[t[2]] - p0;
    const Eigen::Vector3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-14) continue;
    const double inv = 1.0 / det;
    const Eigen::Vector3d s = base - p0;
    const double u = s.dot(p) * inv;
    if (u < -1e-12 || u > 1 + 1e-12) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = d.dot(q) * inv;
    if (v < -1e-12 || u + v > 1 + 1e-12) continue;
    const double along = e2.dot(q) * inv;
    if (!best || along > *best) best = along;
  }
  return best;
}

}  // namespace

std::vector<double> crushProfile(const deform::ControlMesh& mesh,
                                 const std::vector<Eigen::Vector3d>& points_m,
                                 const Eigen::Vector3d& direction, double z_m, int stations) {
  return crushProfile(mesh.triangles, mesh.points_m, points_m, direction, z_m, stations);
}

std::vector<double> crushProfile(const std::vector<std::array<uint32_t, 3>>& triangles,
                                 const std::vector<Eigen::Vector3d>& rest_m,
                                 const std::vector<Eigen::Vector3d>& now_m, const Eigen::Vector3d& direction,
                                 double z_m, int stations) {
  std::vector<double> out;
  Eigen::Vector3d d(direction.x(), direction.y(), 0);
  if (d.norm() < 1e-12 || stations < 1 || now_m.size() != rest_m.size()) return out;
  d.normalize();
  const Eigen::Vector3d lateral = Eigen::Vector3d::UnitZ().cross(d);
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const auto& p : rest_m) {
    low = std::min(low, lateral.dot(p));
    high = std::max(high, lateral.dot(p));
  }
  for (int j = 0; j < stations; ++j) {
    const double y = low + (j + 0.5) * (high - low) / stations;
    const Eigen::Vector3d base = y * lateral + Eigen::Vector3d(0, 0, z_m);
    const auto rest = furthestHit(triangles, rest_m, base, d);
    const auto now = furthestHit(triangles, now_m, base, d);
    // A station whose line passes above or below the surface (a coarse hull's chamfered end) has no
    // value: NaN keeps the others at their stations.
    out.push_back(rest && now ? std::max(0.0, *rest - *now) : std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

CrushStations crushStations(const std::vector<std::array<uint32_t, 3>>& triangles,
                            const std::vector<Eigen::Vector3d>& rest_m,
                            const std::vector<Eigen::Vector3d>& now_m, const Eigen::Vector3d& direction) {
  CrushStations out;
  if (rest_m.empty()) return out;
  std::size_t lead = 0;
  for (std::size_t i = 1; i < rest_m.size(); ++i)
    if (rest_m[i].dot(direction) > rest_m[lead].dot(direction)) lead = i;
  out.height_m = rest_m[lead].z();
  out.profile_m = crushProfile(triangles, rest_m, now_m, direction, out.height_m);
  double sum = 0;
  std::size_t hits = 0;
  for (double c : out.profile_m) {
    if (std::isnan(c)) continue;  // the station's line misses the surface
    sum += c;
    ++hits;
    out.max_m = std::max(out.max_m, c);
  }
  if (hits > 0) out.mean_m = sum / static_cast<double>(hits);
  return out;
}

}  // namespace vehicle
