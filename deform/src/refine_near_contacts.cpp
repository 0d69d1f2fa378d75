// Where a contact asks for a finer surface (refinement.hpp, splitNearContacts).
#include <deform/refinement.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace deform {
namespace {

/// The obstacle's smallest radius of curvature seen from `samples` [m]: over pairs of the surface points
/// nearest them, their distance over the angle between the surface's normals there (infinite when the
/// normals all agree: a flat face).
double localRadius(const ContactShape& shape, const std::array<Eigen::Vector3d, 7>& samples,
                   double margin_m) {
  std::array<Eigen::Vector3d, 7> surface, normal;
  std::size_t found = 0;
  for (const Eigen::Vector3d& p : samples) {
    Penetration q;
    if (!penetration(shape, p, q, margin_m)) continue;
    surface[found] = p + q.depth_m * q.normal;
    normal[found] = q.normal;
    ++found;
  }
  constexpr double kSameNormal_rad = 1e-3;
  double radius_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < found; ++i)
    for (std::size_t j = i + 1; j < found; ++j) {
      const double angle_rad = std::atan2(normal[i].cross(normal[j]).norm(), normal[i].dot(normal[j]));
      if (angle_rad > kSameNormal_rad)
        radius_m = std::min(radius_m, (surface[i] - surface[j]).norm() / angle_rad);
    }
  return radius_m;
}

}  // namespace

RefinementOutcome splitNearContacts(SurfaceHierarchy& hierarchy, std::vector<Eigen::Vector3d>& positions_m,
                                    const std::vector<ContactShape>& shapes, const ContactRefinement& rule) {
  RefinementOutcome outcome;
  for (bool again = !shapes.empty(); again;) {
    again = false;
    const std::size_t nodes = hierarchy.nodes().size();
    for (uint32_t id = 0; id < nodes; ++id) {
      if (!hierarchy.isLeaf(id)) continue;
      const auto& c = hierarchy.nodes()[id].corners;
      // Its size at rest: a patch the crush stretches does not split again for that.
      const auto& rest = hierarchy.restPoints();
      const double longest_m = std::max({(rest[c[0]] - rest[c[1]]).norm(), (rest[c[1]] - rest[c[2]]).norm(),
                                         (rest[c[2]] - rest[c[0]]).norm()});
      if (0.5 * longest_m < rule.contact_edge_m) continue;  // its children would be finer than the floor
      const Eigen::Vector3d a = positions_m[c[0]], b = positions_m[c[1]], d = positions_m[c[2]];
      const Eigen::Vector3d centre = (a + b + d) / 3.0;
      const double size_m = std::max({(a - centre).norm(), (b - centre).norm(), (d - centre).norm()});
      const std::array<Eigen::Vector3d, 7> samples = {
          a, b, d, 0.5 * (a + b), 0.5 * (b + d), 0.5 * (d + a), centre};
      double allowed_m = std::numeric_limits<double>::infinity();
      for (const ContactShape& shape : shapes) {
        Penetration near;
        if (!penetration(shape, centre, near, size_m + rule.reach_m)) continue;
        allowed_m = std::min(allowed_m,
                             rule.edge_per_radius * localRadius(shape, samples, 2.0 * size_m + rule.reach_m));
      }
      if (!(longest_m > allowed_m)) continue;
      const std::size_t before = hierarchy.restPoints().size();
      // A leaf has one split edge at most (closure), so its split adds two points at least: past that, no
      // split can fit, and none is tried (each try is made and undone).
      if (before + 2 > rule.max_points) {
        outcome.bounded = true;
        return outcome;
      }
      if (!hierarchy.split(id, rule.max_points)) {
        outcome.bounded = true;
        continue;
      }
      ++outcome.splits;
      again = true;
      for (std::size_t k = before; k < hierarchy.restPoints().size(); ++k) {
        const auto [p, q] = hierarchy.parentsOf(static_cast<uint32_t>(k));
        positions_m.push_back(0.5 * (positions_m[p] + positions_m[q]));
      }
    }
  }
  return outcome;
}

}  // namespace deform
