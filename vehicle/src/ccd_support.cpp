// libccd callbacks for ObstacleShape and a point-in-shape penetration query (MPR).
#include <vehicle/ccd_support.hpp>

#include <algorithm>

#include <cmath>

namespace vehicle {
namespace {

Eigen::Vector3d fromCcd(const ccd_vec3_t* v) {
  return {v->v[0], v->v[1], v->v[2]};
}
void toCcd(const Eigen::Vector3d& p, ccd_vec3_t* out) {
  ccdVec3Set(out, p.x(), p.y(), p.z());
}

/// A single point as a libccd object.
void pointSupport(const void* point, const ccd_vec3_t* /*direction*/, ccd_vec3_t* out) {
  toCcd(*static_cast<const Eigen::Vector3d*>(point), out);
}
void pointCentre(const void* point, ccd_vec3_t* out) {
  toCcd(*static_cast<const Eigen::Vector3d*>(point), out);
}

/// libccd's MPR set-up: object 1 an ObstacleShape, object 2 by the given functions.
ccd_t mprAgainst(ccd_support_fn support2, ccd_center_fn centre2);

}  // namespace

void ccdSupport(const void* obstacle_shape, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  toCcd(supportPoint(*static_cast<const ObstacleShape*>(obstacle_shape), fromCcd(direction)), out);
}

void ccdCentre(const void* obstacle_shape, ccd_vec3_t* out) {
  toCcd(interiorPoint(*static_cast<const ObstacleShape*>(obstacle_shape)), out);
}

namespace {
ccd_t mprAgainst(ccd_support_fn support2, ccd_center_fn centre2) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccdSupport;
  ccd.center1 = ccdCentre;
  ccd.support2 = support2;
  ccd.center2 = centre2;
  ccd.mpr_tolerance = 1e-9;
  return ccd;
}
}  // namespace

bool pointPenetration(const ObstacleShape& shape, const Eigen::Vector3d& point_m, Eigen::Vector3d& out_normal,
                      double& out_depth_m) {
  if (shape.type == ShapeType::HalfSpace) {
    out_depth_m = shape.offset_m - shape.normal.dot(point_m);
    out_normal = shape.normal;
    return out_depth_m > 0;
  }
  if (shape.type == ShapeType::Sphere) {
    const Eigen::Vector3d d = point_m - shape.centre_m;
    const double distance = d.norm();
    out_depth_m = shape.radius_m - distance;
    out_normal = distance > 1e-12 ? Eigen::Vector3d(d / distance) : Eigen::Vector3d::UnitZ();
    return out_depth_m > 0;
  }
  if ((point_m - interiorPoint(shape)).norm() > boundingRadius(shape)) return false;
  ccd_t ccd = mprAgainst(pointSupport, pointCentre);
  ccd_real_t depth = 0;
  ccd_vec3_t direction, position;
  if (ccdMPRPenetration(&shape, &point_m, &ccd, &depth, &direction, &position) != 0) return false;
  // libccd's direction moves object 2 (the point) out of object 1 (the shape).
  out_normal = fromCcd(&direction);
  out_depth_m = depth;
  return depth > 0;
}

double overlapDepth_m(const ObstacleShape& a, const ObstacleShape& b) {
  if (a.type == ShapeType::HalfSpace || b.type == ShapeType::HalfSpace) return 0;
  if ((interiorPoint(a) - interiorPoint(b)).norm() > boundingRadius(a) + boundingRadius(b)) return 0;
  ccd_t ccd = mprAgainst(ccdSupport, ccdCentre);
  ccd_real_t depth = 0;
  ccd_vec3_t direction, position;
  if (ccdMPRPenetration(&a, &b, &ccd, &depth, &direction, &position) != 0) return 0;
  return std::max(0.0, static_cast<double>(depth));
}

}  // namespace vehicle
