#pragma once
// Internal helpers of the built-in meshes: smooth 1D profiles through control points, planar curves
// sampled evenly by arc length, and the welded ring grid between two poles that shapes are lofted on.
#include <deform/mesh.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

namespace deform::builtin {

/// A smooth function through control points (x ascending), monotone between them: piecewise cubic
/// Hermite with Fritsch-Carlson slopes (Fritsch & Carlson 1980, SIAM J. Numer. Anal. 17(2)), so a
/// profile never overshoots its control points. Constant beyond the first and last point.
class SmoothProfile {
 public:
  explicit SmoothProfile(std::vector<std::pair<double, double>> points);
  double operator()(double x) const;

 private:
  std::vector<double> x_, y_, slope_;
};

/// A planar curve of straight lines and circular arcs, sampled evenly by arc length. Sampling by
/// arc length means a segment that shrinks to zero length never yields coincident vertices.
class ProfileCurve {
 public:
  void clear() { segments_.clear(); }
  void moveTo(const Eigen::Vector2d& p) { cursor_ = p; }
  /// Straight line from the end of the previous segment (or the moveTo point).
  void lineTo(const Eigen::Vector2d& p);
  /// Circular arc around `centre`, angles in radians (counter-clockwise when to > from).
  void arc(const Eigen::Vector2d& centre, double radius_m, double from_rad, double to_rad);
  double length_m() const;
  /// `count` >= 2 points evenly spaced by arc length; the first and last are exactly the ends.
  void sample(std::size_t count, Eigen::Vector2d* out) const;

 private:
  struct Segment {
    Eigen::Vector2d start{0, 0}, end{0, 0}, centre{0, 0};
    double radius_m = 0, from_rad = 0, to_rad = 0, length_m = 0;
    bool is_arc = false;
    Eigen::Vector2d at(double fraction) const;
  };
  std::vector<Segment> segments_;
  Eigen::Vector2d cursor_{0, 0};
};

/// `count` points along the polyline through `corners`, every corner among them when there are enough
/// points (so sharp features such as a can's rim stay sharp), the rest spread in proportion to length.
void samplePolyline(const std::vector<Eigen::Vector2d>& corners, std::size_t count, Eigen::Vector2d* out);

/// Vertex index in a pole grid: the start pole is 0, ring r (0-based) occupies ring_size indices after
/// it, the end pole is last.
inline uint32_t ringVertex(std::size_t ring, std::size_t j, std::size_t ring_size) {
  return static_cast<uint32_t>(1 + ring * ring_size + j);
}

/// Sizes `mesh` for `rings` rings of `ring_size` vertices between a start and an end pole and writes
/// the triangles, welded around each ring and at the poles. Winding: with d_ring the direction from
/// ring to ring (start to end pole) and d_j the direction along a ring, the outward normal is
/// d_j x d_ring; callers place their vertices so that holds.
void poleGridTopology(std::size_t rings, std::size_t ring_size, Mesh& mesh);

/// Triangle-by-triangle signed volume [m^3] of a closed mesh (positive when wound outward).
double signedVolume_m3(const Mesh& mesh);

}  // namespace deform::builtin
