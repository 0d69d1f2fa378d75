// A closed triangulation of points that all lie on a convex surface, including points in the middle of
// its flat faces (which a convex hull drops as not extreme): the hull of the points, the dropped points
// inserted into the faces they lie on, then Delaunay edge flips inside each flat region so the
// triangles there are as round as they can be (Lawson's flip algorithm).
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>

#include "point_bounds.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

namespace deform {
namespace {

using Directed = std::pair<uint32_t, uint32_t>;

/// Largest bend between two triangles across which an edge may be flipped [degrees].
constexpr double kFlatDegrees = 30.0;
/// Largest fold a flip may make, as a fraction of the new edge's length.
constexpr double kMaxFoldRatio = 0.02;

/// The triangles whose distance to a point (SurfaceBuilder::distanceToTriangle) can be at most
/// `reach_m`: each listed in the cells of a uniform grid that its bounding box, grown by reach_m / kappa,
/// overlaps. kappa = min(1, sqrt(2 area) / (4 longest edge)) bounds the distance from below: a point at
/// Euclidean distance e from the triangle, e <= |p - q| + 4 m L where q is its projection onto the plane
/// and m its most negative barycentric coordinate, has distance |p - q| + m sqrt(2 area) >= kappa e.
class TriangleCells {
 public:
  /// A grid of cells of about `cell_m` over the box lo..hi (at most about a million cells).
  TriangleCells(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double cell_m, double reach_m)
      : lo_(lo), reach_m_(reach_m) {
    const Eigen::Vector3d size = (hi - lo).cwiseMax(1e-12);
    cell_m_ = std::max(cell_m, std::cbrt(size.prod() / 1e6));
    counts_ = ((size / cell_m_).array().floor() + 1).cast<int>().matrix();
    cells_.resize(static_cast<std::size_t>(counts_.prod()));
  }
  double reach_m() const { return reach_m_; }

  /// Lists (add) or unlists triangle t with corners a, b, c; a triangle of no area is never listed (its
  /// distance is infinite).
  void update(uint32_t t, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
              bool add) {
    const double twice_area = (b - a).cross(c - a).norm();
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (!(twice_area > 0)) return;
    const double kappa = std::min(1.0, std::sqrt(twice_area) / (4 * longest));
    // 1e-6 relative to spare the rounding of the bound's own terms.
    const double grow_m = reach_m_ / kappa * (1 + 1e-6);
    const Eigen::Vector3i first = clamped(a.cwiseMin(b).cwiseMin(c).array() - grow_m);
    const Eigen::Vector3i last = clamped(a.cwiseMax(b).cwiseMax(c).array() + grow_m);
    for (int i = first.x(); i <= last.x(); ++i)
      for (int j = first.y(); j <= last.y(); ++j)
        for (int k = first.z(); k <= last.z(); ++k) {
          std::vector<uint32_t>& list = cells_[index({i, j, k})];
          if (add) {
            list.push_back(t);
          } else {
            const auto at = std::find(list.begin(), list.end(), t);
            if (at != list.end()) list.erase(at);
          }
        }
  }

  /// The triangles listed in p's cell; null for a place outside the grid.
  const std::vector<uint32_t>* near(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d at = (p - lo_) / cell_m_;
    if (!(at.array() >= 0).all() || !(at.array() < counts_.cast<double>().array()).all()) return nullptr;
    return &cells_[index(at.array().floor().cast<int>())];
  }

 private:
  /// The cell of p, clamped into the grid (a triangle is listed in every cell of the grid its grown box
  /// meets).
  Eigen::Vector3i clamped(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d at =
        ((p - lo_) / cell_m_).cwiseMax(0.0).cwiseMin((counts_.array() - 1).matrix().cast<double>());
    return at.array().floor().cast<int>();
  }
  std::size_t index(const Eigen::Vector3i& c) const {
    return static_cast<std::size_t>(c.x()) +
           static_cast<std::size_t>(counts_.x()) *
               (static_cast<std::size_t>(c.y()) +
                static_cast<std::size_t>(counts_.y()) * static_cast<std::size_t>(c.z()));
  }

  Eigen::Vector3d lo_;
  double cell_m_ = 0, reach_m_;
  Eigen::Vector3i counts_;
  std::vector<std::vector<uint32_t>> cells_;
};

class SurfaceBuilder {
 public:
  /// `cell_m`: the grid of TriangleCells, about the spacing of the points to insert.
  SurfaceBuilder(ControlMesh& mesh, double cell_m, double extent_m, bool by_cells)
      : mesh_(mesh),
        cells_(detail::lowest(mesh.points_m), detail::highest(mesh.points_m), cell_m, 1e-6 * extent_m),
        rounding_m_(1e-9 * extent_m),
        by_cells_(by_cells) {
    for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) link(t);
  }

  /// Inserts p into the face it lies on: splits the triangle (or, on an edge, the two beside it).
  void insert(const Eigen::Vector3d& p) {
    // The face nearest p by distanceToTriangle, the lowest index among equals: among the triangles
    // listed near p when the nearest of them is within the cells' reach (every other is then further),
    // else among all.
    uint32_t best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    Eigen::Vector3d best_bary = Eigen::Vector3d::Constant(1.0 / 3.0);
    auto consider = [&](uint32_t t) {
      Eigen::Vector3d bary = Eigen::Vector3d::Zero();
      const double d = distanceToTriangle(p, t, bary);
      if (d < best_distance || (d == best_distance && t < best))
        best_distance = d, best = t, best_bary = bary;
    };
    if (const std::vector<uint32_t>* near = by_cells_ ? cells_.near(p) : nullptr)
      for (uint32_t t : *near) consider(t);
    if (!by_cells_ || !(best_distance + rounding_m_ <= cells_.reach_m())) {
      best = 0;
      best_distance = std::numeric_limits<double>::infinity();
      best_bary = Eigen::Vector3d::Constant(1.0 / 3.0);
      for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) consider(t);
    }
    const auto v = static_cast<uint32_t>(mesh_.points_m.size());
    const auto tri = mesh_.triangles[best];
    const double on_edge = 1e-9;
    const auto zeros = (best_bary.array() < on_edge).count();
    if (zeros >= 2) return;  // on a vertex: already there
    mesh_.points_m.push_back(p);
    if (zeros == 0) {  // inside: one triangle becomes three
      unlink(best);
      mesh_.triangles[best] = {tri[0], tri[1], v};
      link(best);
      addTriangle({tri[1], tri[2], v});
      addTriangle({tri[2], tri[0], v});
      return;
    }
    // On the edge opposite the zero coordinate: both triangles beside it become two each.
    int k = 0;
    best_bary.minCoeff(&k);
    const uint32_t a = tri[static_cast<std::size_t>((k + 1) % 3)],
                   b = tri[static_cast<std::size_t>((k + 2) % 3)];
    const uint32_t c = tri[static_cast<std::size_t>(k)];
    const uint32_t other = owner_.at({b, a});
    const auto& o = mesh_.triangles[other];
    uint32_t d = o[0] + o[1] + o[2] - a - b;  // the vertex of `other` off the edge
    replacePair(best, {a, v, c}, other, {v, a, d});
    addTriangle({v, b, c});
    addTriangle({b, v, d});
  }

  /// Flips edges inside flat regions until every such edge is locally Delaunay (no more insertions).
  void flipFlatRegions() {
    inserting_ = false;
    for (int pass = 0; pass < 100; ++pass) {
      int flips = 0;
      for (uint32_t t = 0; t < mesh_.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) flips += tryFlip(t, k);
      if (flips == 0) return;
    }
  }

 private:
  void link(uint32_t t) {
    const auto& tri = mesh_.triangles[t];
    for (int k = 0; k < 3; ++k)
      owner_[{tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]}] = t;
    if (inserting_ && by_cells_)
      cells_.update(t, mesh_.points_m[tri[0]], mesh_.points_m[tri[1]], mesh_.points_m[tri[2]], true);
  }
  void unlink(uint32_t t) {
    const auto& tri = mesh_.triangles[t];
    for (int k = 0; k < 3; ++k)
      owner_.erase({tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]});
    if (inserting_ && by_cells_)
      cells_.update(t, mesh_.points_m[tri[0]], mesh_.points_m[tri[1]], mesh_.points_m[tri[2]], false);
  }
  /// Two neighbouring triangles rewritten at once (their shared edge changes).
  void replacePair(uint32_t t, const std::array<uint32_t, 3>& new_t, uint32_t u,
                   const std::array<uint32_t, 3>& new_u) {
    unlink(t);
    unlink(u);
    mesh_.triangles[t] = new_t;
    mesh_.triangles[u] = new_u;
    link(t);
    link(u);
  }
  void addTriangle(const std::array<uint32_t, 3>& tri) {
    mesh_.triangles.push_back(tri);
    link(static_cast<uint32_t>(mesh_.triangles.size() - 1));
  }

  double distanceToTriangle(const Eigen::Vector3d& p, uint32_t t, Eigen::Vector3d& bary) const {
    const auto& tri = mesh_.triangles[t];
    const Eigen::Vector3d a = mesh_.points_m[tri[0]], b = mesh_.points_m[tri[1]], c = mesh_.points_m[tri[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area2 = n.squaredNorm();
    if (area2 == 0) return std::numeric_limits<double>::infinity();
    const Eigen::Vector3d q = p - n * (n.dot(p - a) / area2);  // projection onto the plane
    bary = Eigen::Vector3d(n.dot((c - b).cross(q - b)), n.dot((a - c).cross(q - c)),
                           n.dot((b - a).cross(q - a))) /
           area2;
    const double outside = std::max(0.0, -bary.minCoeff()) * std::sqrt(std::sqrt(area2));
    return (p - q).norm() + outside;
  }

  /// Angle at `apex` in the triangle (apex, u, w).
  double angle(uint32_t apex, uint32_t u, uint32_t w) const {
    const Eigen::Vector3d x = mesh_.points_m[u] - mesh_.points_m[apex],
                          y = mesh_.points_m[w] - mesh_.points_m[apex];
    return std::atan2(x.cross(y).norm(), x.dot(y));
  }

  int tryFlip(uint32_t t, int k) {
    const auto tri = mesh_.triangles[t];
    const uint32_t a = tri[static_cast<std::size_t>(k)], b = tri[static_cast<std::size_t>((k + 1) % 3)],
                   l = tri[static_cast<std::size_t>((k + 2) % 3)];
    auto twin = owner_.find({b, a});
    if (twin == owner_.end()) return 0;
    const uint32_t u = twin->second;
    const auto& o = mesh_.triangles[u];
    const uint32_t r = o[0] + o[1] + o[2] - a - b;
    if (owner_.count({l, r}) || owner_.count({r, l})) return 0;  // the other diagonal exists already
    // Only inside a (nearly) flat region: the two triangles' normals within kFlatDegrees. Across a real
    // crease the hull's edge stays; a flip across a slight bend moves the surface inward by a fraction
    // of a millimetre per metre of edge, which is well inside what a dent moves it.
    const Eigen::Vector3d pa = mesh_.points_m[a], pb = mesh_.points_m[b];
    const Eigen::Vector3d n = (pb - pa).cross(mesh_.points_m[l] - pa);
    const Eigen::Vector3d m = (pa - pb).cross(mesh_.points_m[r] - pb);
    if (n.norm() == 0 || m.norm() == 0 ||
        n.normalized().dot(m.normalized()) < std::cos(kFlatDegrees * M_PI / 180))
      return 0;
    if (angle(l, a, b) + angle(r, b, a) <= M_PI + 1e-12) return 0;  // already locally Delaunay
    // The fold a flip makes is the distance between the two diagonals (they cross in a flat quad);
    // keep it under kMaxFoldRatio of the new edge so the surface stays close to the hull.
    const Eigen::Vector3d across = (pb - pa).cross(mesh_.points_m[r] - mesh_.points_m[l]);
    if (across.norm() == 0) return 0;
    const double fold_m = std::abs((mesh_.points_m[l] - pa).dot(across)) / across.norm();
    if (fold_m > kMaxFoldRatio * (mesh_.points_m[r] - mesh_.points_m[l]).norm()) return 0;
    // The quad (a, r, b, l) must be convex for the new diagonal l-r to lie inside it: both new
    // triangles keep the outward winding.
    const Eigen::Vector3d pl = mesh_.points_m[l], pr = mesh_.points_m[r];
    if (n.dot((pa - pl).cross(pr - pl)) <= 0 || n.dot((pb - pr).cross(pl - pr)) <= 0) return 0;
    replacePair(t, {l, a, r}, u, {r, b, l});
    return 1;
  }

  ControlMesh& mesh_;
  std::map<Directed, uint32_t> owner_;  ///< directed edge -> the triangle that has it
  TriangleCells cells_;                 ///< while inserting: the triangles near each place
  double rounding_m_;                   ///< spare for the rounding of distanceToTriangle [m]
  bool by_cells_;                       ///< false: every triangle is a candidate (the reference)
  bool inserting_ = true;
};

}  // namespace

ControlMesh triangulateOnConvexSurface(const std::vector<Eigen::Vector3d>& points, const char* source,
                                       bool nearest_by_cells) {
  ControlMesh mesh = convexHull(points, source, FacetSplit::Diagonals);
  std::map<std::array<double, 3>, bool> is_vertex;
  for (const auto& p : mesh.points_m) is_vertex[{p.x(), p.y(), p.z()}] = true;
  // Cells about the spacing of the points on the hull's surface.
  double area_m2 = 0, extent_m = 0;
  for (const auto& t : mesh.triangles)
    area_m2 +=
        0.5 *
        (mesh.points_m[t[1]] - mesh.points_m[t[0]]).cross(mesh.points_m[t[2]] - mesh.points_m[t[0]]).norm();
  for (const auto& p : mesh.points_m) extent_m = std::max(extent_m, p.cwiseAbs().maxCoeff());
  const double cell_m =
      std::max(2 * std::sqrt(area_m2 / static_cast<double>(points.size())), 1e-6 * extent_m);
  SurfaceBuilder builder(mesh, cell_m, std::max(extent_m, 1e-12), nearest_by_cells);
  for (const auto& p : points)
    if (!is_vertex.count({p.x(), p.y(), p.z()})) builder.insert(p);
  builder.flipFlatRegions();
  finishControlMesh(mesh);
  return mesh;
}

}  // namespace deform
