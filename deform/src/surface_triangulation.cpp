// A closed triangulation of points that all lie on a convex surface, including points in the middle of
// its flat faces (which a convex hull drops as not extreme): the hull of the points, the dropped points
// inserted into the faces they lie on, then Delaunay edge flips inside each flat region so the
// triangles there are as round as they can be (Lawson's flip algorithm).
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <map>

namespace deform {
namespace {

using Directed = std::pair<uint32_t, uint32_t>;

/// Largest bend between two triangles across which an edge may be flipped [degrees].
constexpr double kFlatDegrees = 30.0;
/// Largest fold a flip may make, as a fraction of the new edge's length.
constexpr double kMaxFoldRatio = 0.02;

class SurfaceBuilder {
 public:
  explicit SurfaceBuilder(ControlMesh& mesh) : mesh_(mesh) {
    for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) link(t);
  }

  /// Inserts p into the face it lies on: splits the triangle (or, on an edge, the two beside it).
  void insert(const Eigen::Vector3d& p) {
    uint32_t best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    Eigen::Vector3d best_bary = Eigen::Vector3d::Constant(1.0 / 3.0);
    for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
      Eigen::Vector3d bary = Eigen::Vector3d::Zero();
      double d = distanceToTriangle(p, t, bary);
      if (d < best_distance) best_distance = d, best = t, best_bary = bary;
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

  /// Flips edges inside flat regions until every such edge is locally Delaunay.
  void flipFlatRegions() {
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
  }
  void unlink(uint32_t t) {
    const auto& tri = mesh_.triangles[t];
    for (int k = 0; k < 3; ++k)
      owner_.erase({tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]});
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
};

}  // namespace

ControlMesh triangulateOnConvexSurface(const std::vector<Eigen::Vector3d>& points, const char* source) {
  ControlMesh mesh = convexHull(points, source, FacetSplit::Diagonals);
  std::map<std::array<double, 3>, bool> is_vertex;
  for (const auto& p : mesh.points_m) is_vertex[{p.x(), p.y(), p.z()}] = true;
  SurfaceBuilder builder(mesh);
  for (const auto& p : points)
    if (!is_vertex.count({p.x(), p.y(), p.z()})) builder.insert(p);
  builder.flipFlatRegions();
  finishControlMesh(mesh);
  return mesh;
}

}  // namespace deform
