#include "builtin_grid.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace deform::builtin {

SmoothProfile::SmoothProfile(std::vector<std::pair<double, double>> points) {
  assert(points.size() >= 2);
  for (const auto& [x, y] : points) {
    assert(x_.empty() || x > x_.back());
    x_.push_back(x);
    y_.push_back(y);
  }
  const std::size_t n = x_.size();
  std::vector<double> secant(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) secant[i] = (y_[i + 1] - y_[i]) / (x_[i + 1] - x_[i]);
  slope_.assign(n, 0.0);
  slope_[0] = secant[0];
  slope_[n - 1] = secant[n - 2];
  for (std::size_t i = 1; i + 1 < n; ++i) {
    // A local extremum gets a flat tangent; otherwise the weighted harmonic mean keeps it monotone.
    if (secant[i - 1] * secant[i] <= 0) continue;
    const double h0 = x_[i] - x_[i - 1], h1 = x_[i + 1] - x_[i];
    const double w0 = 2 * h1 + h0, w1 = h1 + 2 * h0;
    slope_[i] = (w0 + w1) / (w0 / secant[i - 1] + w1 / secant[i]);
  }
}

double SmoothProfile::operator()(double x) const {
  if (x <= x_.front()) return y_.front();
  if (x >= x_.back()) return y_.back();
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin()) - 1;
  const double h = x_[i + 1] - x_[i], t = (x - x_[i]) / h;
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * y_[i] + (t3 - 2 * t2 + t) * h * slope_[i] + (-2 * t3 + 3 * t2) * y_[i + 1] +
         (t3 - t2) * h * slope_[i + 1];
}

void ProfileCurve::lineTo(const Eigen::Vector2d& p) {
  Segment s;
  s.start = cursor_;
  s.end = p;
  s.length_m = (p - cursor_).norm();
  segments_.push_back(s);
  cursor_ = p;
}

void ProfileCurve::arc(const Eigen::Vector2d& centre, double radius_m, double from_rad, double to_rad) {
  Segment s;
  s.is_arc = true;
  s.centre = centre;
  s.radius_m = radius_m;
  s.from_rad = from_rad;
  s.to_rad = to_rad;
  s.start = s.at(0);
  s.end = s.at(1);
  s.length_m = std::abs(to_rad - from_rad) * radius_m;
  segments_.push_back(s);
  cursor_ = s.end;
}

Eigen::Vector2d ProfileCurve::Segment::at(double fraction) const {
  if (!is_arc) return start + fraction * (end - start);
  const double angle = from_rad + fraction * (to_rad - from_rad);
  return centre + radius_m * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

double ProfileCurve::length_m() const {
  double total = 0;
  for (const auto& s : segments_) total += s.length_m;
  return total;
}

void ProfileCurve::sample(std::size_t count, Eigen::Vector2d* out) const {
  assert(count >= 2 && !segments_.empty());
  const double total = length_m();
  std::size_t seg = 0;
  double seg_start = 0;  // arc length at the start of segment `seg`
  for (std::size_t k = 0; k < count; ++k) {
    const double s = total * static_cast<double>(k) / static_cast<double>(count - 1);
    while (seg + 1 < segments_.size() && s > seg_start + segments_[seg].length_m) {
      seg_start += segments_[seg].length_m;
      ++seg;
    }
    const Segment& g = segments_[seg];
    const double fraction = g.length_m > 0 ? std::clamp((s - seg_start) / g.length_m, 0.0, 1.0) : 1.0;
    out[k] = g.at(fraction);
  }
  out[0] = segments_.front().start;
  out[count - 1] = segments_.back().end;
}

void samplePolyline(const std::vector<Eigen::Vector2d>& corners, std::size_t count, Eigen::Vector2d* out) {
  assert(corners.size() >= 2 && count >= 2);
  const std::size_t segments = corners.size() - 1, edges = count - 1;
  if (edges < segments) {  // too coarse to keep every corner: even spacing by arc length
    ProfileCurve curve;
    curve.moveTo(corners.front());
    for (std::size_t i = 1; i < corners.size(); ++i) curve.lineTo(corners[i]);
    curve.sample(count, out);
    return;
  }
  std::vector<double> length_m(segments);
  double total_m = 0;
  for (std::size_t i = 0; i < segments; ++i) total_m += length_m[i] = (corners[i + 1] - corners[i]).norm();
  // One edge per segment, the spare edges by length with the largest remainders rounded up.
  const std::size_t spare = edges - segments;
  std::vector<std::size_t> share(segments);
  std::vector<std::pair<double, std::size_t>> remainder(segments);
  std::size_t given = 0;
  for (std::size_t i = 0; i < segments; ++i) {
    const double exact = static_cast<double>(spare) * length_m[i] / total_m;
    share[i] = 1 + static_cast<std::size_t>(exact);
    given += share[i] - 1;
    remainder[i] = {-(exact - std::floor(exact)), i};
  }
  std::sort(remainder.begin(), remainder.end());
  for (std::size_t k = 0; given < spare; ++k, ++given) ++share[remainder[k].second];
  std::size_t next = 0;
  for (std::size_t i = 0; i < segments; ++i) {
    for (std::size_t k = 0; k < share[i]; ++k) {
      const double f = static_cast<double>(k) / static_cast<double>(share[i]);
      out[next++] = corners[i] + f * (corners[i + 1] - corners[i]);
    }
  }
  out[next] = corners.back();
}

void poleGridTopology(std::size_t rings, std::size_t ring_size, Mesh& mesh) {
  assert(rings >= 1 && ring_size >= 3);
  const std::size_t vertices = rings * ring_size + 2;
  assert(vertices < std::numeric_limits<uint32_t>::max());
  mesh.positions_m.assign(vertices, Eigen::Vector3f::Zero());
  mesh.normals.clear();
  mesh.triangles.clear();
  mesh.triangles.reserve(2 * ring_size * rings);
  const uint32_t start_pole = 0, end_pole = static_cast<uint32_t>(vertices - 1);
  for (std::size_t j = 0; j < ring_size; ++j) {
    const std::size_t jn = (j + 1) % ring_size;
    mesh.triangles.push_back({start_pole, ringVertex(0, jn, ring_size), ringVertex(0, j, ring_size)});
  }
  for (std::size_t r = 0; r + 1 < rings; ++r) {
    for (std::size_t j = 0; j < ring_size; ++j) {
      const std::size_t jn = (j + 1) % ring_size;
      const uint32_t a = ringVertex(r, j, ring_size), b = ringVertex(r, jn, ring_size);
      const uint32_t c = ringVertex(r + 1, jn, ring_size), d = ringVertex(r + 1, j, ring_size);
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  }
  for (std::size_t j = 0; j < ring_size; ++j) {
    const std::size_t jn = (j + 1) % ring_size;
    mesh.triangles.push_back(
        {ringVertex(rings - 1, j, ring_size), ringVertex(rings - 1, jn, ring_size), end_pole});
  }
}

double signedVolume_m3(const Mesh& mesh) {
  double six_volume = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions_m[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.positions_m[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions_m[t[2]].cast<double>();
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

}  // namespace deform::builtin
