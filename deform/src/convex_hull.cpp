// Convex hull through qhull (reentrant API), triangulated ("Qt"), wound outward.
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace deform {
namespace {

/// Distinct points (exact duplicates removed, first occurrence kept, order preserved).
std::vector<Eigen::Vector3d> distinctPoints(const std::vector<Eigen::Vector3d>& points) {
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto less = [&](std::size_t a, std::size_t b) {
    const auto &p = points[a], &q = points[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<char> keep(points.size(), 0);
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || points[order[k]] != points[order[k - 1]]) keep[order[k]] = 1;
  }
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (keep[i]) out.push_back(points[i]);
  return out;
}

/// Refuses inputs with no volume before qhull sees them, with a message a user can act on.
void checkSpansVolume(const std::vector<Eigen::Vector3d>& points, const std::string& where) {
  if (points.size() < 4)
    throw InputError(where + ": a convex hull needs at least 4 distinct points (got " +
                     std::to_string(points.size()) + ")");
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) {
    if (!p.allFinite()) throw InputError(where + ": a point has a non-finite coordinate");
    mean += p;
  }
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending spreads
  if (ev[2] <= 0) throw InputError(where + ": all points coincide");
  if (ev[1] <= 1e-9 * ev[2]) throw InputError(where + ": points are collinear (no volume to enclose)");
  if (ev[0] <= 1e-9 * ev[2]) throw InputError(where + ": points are flat (coplanar; no volume to enclose)");
}

/// Triangulates one hull facet with outward winding. A triangle is taken as it is. A merged facet of 4
/// or more coplanar corners (which every mirror-symmetric body has: the isosceles trapezoids across its
/// plane of symmetry are cocircular) is fanned from its centroid, a new control point: a diagonal would
/// be an arbitrary choice that breaks the symmetry of the masses and of the constraints.
void appendFacet(ControlMesh& hull, std::vector<uint32_t> corners, const Eigen::Vector3d& outward) {
  auto wind = [&](std::array<uint32_t, 3> tri) {
    const auto &a = hull.points_m[tri[0]], &b = hull.points_m[tri[1]], &c = hull.points_m[tri[2]];
    if ((b - a).cross(c - a).dot(outward) < 0) std::swap(tri[1], tri[2]);
    hull.triangles.push_back(tri);
  };
  if (corners.size() == 3) return wind({corners[0], corners[1], corners[2]});
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (uint32_t c : corners) centroid += hull.points_m[c];
  centroid /= static_cast<double>(corners.size());
  // Order the corners by angle around the outward normal, in the facet's plane.
  Eigen::Vector3d u = (hull.points_m[corners[0]] - centroid).normalized();
  Eigen::Vector3d w = outward.cross(u);
  std::sort(corners.begin(), corners.end(), [&](uint32_t a, uint32_t b) {
    Eigen::Vector3d pa = hull.points_m[a] - centroid, pb = hull.points_m[b] - centroid;
    return std::atan2(pa.dot(w), pa.dot(u)) < std::atan2(pb.dot(w), pb.dot(u));
  });
  const auto centre = static_cast<uint32_t>(hull.points_m.size());
  hull.points_m.push_back(centroid);
  for (std::size_t k = 0; k < corners.size(); ++k)
    wind({centre, corners[k], corners[(k + 1) % corners.size()]});
}

/// Every directed edge has its twin: the triangles close a surface.
bool closedSurface(const ControlMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      ++directed[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
  for (const auto& [edge, count] : directed) {
    const auto twin = directed.find({edge.second, edge.first});
    if (count != 1 || twin == directed.end() || twin->second != 1) return false;
  }
  return true;
}

}  // namespace

ControlMesh convexHull(const std::vector<Eigen::Vector3d>& input, const char* source, FacetSplit split) {
  const std::string where = source ? source : "mesh";
  std::vector<Eigen::Vector3d> points = distinctPoints(input);
  checkSpansVolume(points, where);

  std::vector<coordT> coords(points.size() * 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int a = 0; a < 3; ++a) coords[3 * i + static_cast<std::size_t>(a)] = points[i][a];

  qhT qh_storage;
  qhT* qh = &qh_storage;
  FILE* err = std::tmpfile();  // qhull reports there; we quote it in the error message
  qh_zero(qh, err);
  // Without "Qt" merged (non-simplicial) facets come out whole and are fanned in appendFacet.
  char fan_options[] = "qhull", diagonal_options[] = "qhull Qt";
  char* options = split == FacetSplit::CentroidFan ? fan_options : diagonal_options;
  int code =
      qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, options, nullptr, err);

  ControlMesh hull;
  std::string qhull_message;
  if (code == 0) {
    std::map<int, uint32_t> remap;  // qhull point id -> control point index, in point order
    facetT* facet;
    vertexT* vertex;
    vertexT** vertexp;
    FORALLvertices {
      remap[qh_pointid(qh, vertex->point)] = 0;
    }
    uint32_t next = 0;
    for (auto& [id, index] : remap) {
      index = next++;
      hull.points_m.push_back(points[static_cast<std::size_t>(id)]);
    }
    hull.hull_vertex_count = hull.points_m.size();
    FORALLfacets {
      std::vector<uint32_t> corners;
      FOREACHvertex_(facet->vertices) {
        corners.push_back(remap[qh_pointid(qh, vertex->point)]);
      }
      const Eigen::Vector3d outward(facet->normal[0], facet->normal[1], facet->normal[2]);
      appendFacet(hull, corners, outward);
    }
  } else {
    std::rewind(err);
    char line[512];
    if (std::fgets(line, sizeof line, err)) qhull_message = line;
    while (!qhull_message.empty() && (qhull_message.back() == '\n' || qhull_message.back() == '\r'))
      qhull_message.pop_back();
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(err);
  if (code != 0) throw InputError(where + ": convex hull failed: " + qhull_message);

  // Deterministic triangle order, independent of qhull's facet list order.
  for (auto& t : hull.triangles) {
    auto m = std::min_element(t.begin(), t.end()) - t.begin();
    std::rotate(t.begin(), t.begin() + m, t.end());
  }
  std::sort(hull.triangles.begin(), hull.triangles.end());
  if (!closedSurface(hull)) {
    // Nearly degenerate points (found by fuzz_mesh_stl) can give merged facets whose corners do not
    // match their neighbours' (a corner on the shared edge of one and not the other), so the centroid fans
    // leave gaps: qhull's own triangulation is taken instead. Should that not close either, the points
    // are refused rather than the program stopping at finishControlMesh's check.
    if (split == FacetSplit::CentroidFan) return convexHull(input, source, FacetSplit::Diagonals);
    throw InputError(where +
                     ": the convex hull of the points is not a closed surface (nearly degenerate "
                     "points)");
  }
  finishControlMesh(hull);
  return hull;
}

}  // namespace deform
