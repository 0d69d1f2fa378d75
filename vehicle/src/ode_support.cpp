// Convex geom data and ray casts against a space.
#include "ode_support.hpp"

#include <cmath>

namespace vehicle::ode {

ConvexData makeConvexData(const std::vector<Eigen::Vector3d>& points,
                          const std::vector<std::array<uint32_t, 3>>& triangles) {
  ConvexData data;
  data.points.reserve(points.size() * 3);
  for (const auto& p : points) data.points.insert(data.points.end(), {p.x(), p.y(), p.z()});
  data.point_count = static_cast<unsigned>(points.size());
  for (const auto& t : triangles) {
    const Eigen::Vector3d n = (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]);
    const double length = n.norm();
    if (!(length > 1e-12)) continue;
    const Eigen::Vector3d unit = n / length;
    data.planes.insert(data.planes.end(), {unit.x(), unit.y(), unit.z(), unit.dot(points[t[0]])});
    data.polygons.insert(data.polygons.end(), {3u, t[0], t[1], t[2]});
    ++data.face_count;
  }
  return data;
}

RayHit castRay(const GeomGrid& geoms, dGeomID ray, const Eigen::Vector3d& origin_m,
               const Eigen::Vector3d& direction, double length_m, dBodyID ignore, std::vector<int>& scratch,
               double min_facing) {
  dGeomRaySetLength(ray, length_m);
  dGeomRaySet(ray, origin_m.x(), origin_m.y(), origin_m.z(), direction.x(), direction.y(), direction.z());
  const Eigen::Vector3d end = origin_m + length_m * direction;
  const Eigen::Vector3d lo = origin_m.cwiseMin(end), hi = origin_m.cwiseMax(end);
  const std::array<dReal, 6> ray_box{lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z()};
  RayHit best;
  geoms.candidates(lo, hi, scratch);
  for (const int i : scratch) {  // ascending, as the space holds them: ties go as they always went
    dGeomID geom = geoms.geom(i);
    if (ignore != nullptr && dGeomGetBody(geom) == ignore) continue;
    if (!boxesMeet(geoms.box(i), ray_box)) continue;
    dContactGeom contact;
    if (dCollide(ray, geom, 1, &contact, sizeof(dContactGeom)) < 1) continue;
    if (best.hit && !(contact.depth < best.distance_m)) continue;
    Eigen::Vector3d normal = vec(contact.normal);
    if (normal.dot(direction) > 0) normal = -normal;
    if (-normal.dot(direction) < min_facing) continue;  // too steep a face: the ray looks on past it
    best.hit = true;
    best.distance_m = contact.depth;
    best.point_m = vec(contact.pos);
    best.normal = normal;
    best.body = dGeomGetBody(geom);
  }
  return best;
}

}  // namespace vehicle::ode
