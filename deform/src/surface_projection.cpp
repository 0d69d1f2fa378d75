// Projection of render vertices out of obstacles (surface_projection.hpp).
#include <deform/surface_projection.hpp>

#include <algorithm>
#include <cmath>
#include <variant>

namespace deform {
namespace {

constexpr int kExitBisections = 40;  // 4 m / 2^40 = 4e-12 m: far below the float spacing of a position

void grow(Aabb& box, const Eigen::Vector3d& p) {
  box.min_m = box.min_m.cwiseMin(p);
  box.max_m = box.max_m.cwiseMax(p);
}

// The part of `clip` below the plane n . x = offset + reach: along the axis where |n| is largest, the
// plane bounds that coordinate given the extremes of the others over the box.
bool halfSpaceBounds(const HalfSpaceShape& s, const Aabb& clip, double reach_m, Aabb& out) {
  const double length = s.normal.norm();
  const Eigen::Vector3d n = s.normal / length;
  const double level = s.offset_m / length + reach_m;
  Eigen::Index k = 0;
  n.cwiseAbs().maxCoeff(&k);
  double rest_min = 0;  // least value of sum_{j != k} n_j x_j over the box
  for (int j = 0; j < 3; ++j)
    if (j != k) rest_min += std::min(n[j] * clip.min_m[j], n[j] * clip.max_m[j]);
  out = clip;
  const double bound = (level - rest_min) / n[k];  // n_k x_k < level - rest
  if (n[k] > 0)
    out.max_m[k] = std::min(out.max_m[k], bound);
  else
    out.min_m[k] = std::max(out.min_m[k], bound);
  return out.min_m[k] <= out.max_m[k];
}

}  // namespace

bool shapeBounds(const ContactShape& shape, const Aabb& clip, double reach_m, Aabb& out) {
  if (const auto* plane = std::get_if<HalfSpaceShape>(&shape))
    return halfSpaceBounds(*plane, clip, reach_m, out);
  Eigen::Vector3d p;
  supportPoint(shape, -Eigen::Vector3d::UnitX(), p);
  out.min_m = out.max_m = p;
  for (int k = 0; k < 3; ++k)
    for (const double sign : {-1.0, 1.0}) {
      supportPoint(shape, sign * Eigen::Vector3d::Unit(k), p);
      grow(out, p);
    }
  out.min_m.array() -= reach_m;
  out.max_m.array() += reach_m;
  return (out.min_m.array() <= clip.max_m.array()).all() && (out.max_m.array() >= clip.min_m.array()).all();
}

bool projectOutOf(const ContactShape& shape, const Eigen::Vector3d& interior_m, Eigen::Vector3d& point_m) {
  Penetration p;
  if (!penetration(shape, point_m, p) || !(p.depth_m > 0)) return false;
  const Eigen::Vector3d inward = interior_m - point_m;
  Penetration probe;
  const bool interior_inside = penetration(shape, interior_m, probe) && probe.depth_m > 0;
  if (p.normal.dot(inward) >= 0 || interior_inside) {
    const Eigen::Vector3d moved = point_m + (p.depth_m + kProjectionClearance_m) * p.normal;
    // Exact for the primitives; MPR's depth on a support shape is an estimate along its direction, so
    // one still inside leaves by the segment to the interior below.
    if (!(penetration(shape, moved, probe) && probe.depth_m > 0) || interior_inside) {
      point_m = moved;
      return true;
    }
  }
  // Where the segment from the point to the car's interior crosses the surface (the entry face of
  // DeformableBody's contacts, contact_shapes.hpp bisectSurface): the side facing the car.
  Eigen::Vector3d outside = interior_m, inside = point_m;
  bisectSurface(shape, outside, inside, kExitBisections);
  point_m = outside + kProjectionClearance_m * inward.normalized();
  return true;
}

void verticesNear(const ContactShape& shape, const VertexGrid& grid, double reach_m,
                  std::vector<uint32_t>& out) {
  Aabb box;
  if (shapeBounds(shape, grid.bounds(), reach_m, box)) grid.query(box, out);
}

}  // namespace deform
