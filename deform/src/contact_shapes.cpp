// Point-in-obstacle queries: exact for half-space, sphere, box and capsule; libccd's MPR for a convex
// shape given by its support function.
#include <deform/contact_shapes.hpp>
#include <deform/error.hpp>

#include <ccd/ccd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "input_checks.hpp"
#include "support_wide.hpp"

namespace deform {
namespace {

// Each query: true when the point is closer than `margin` to the obstacle's surface or inside it; then
// `out.depth_m` is the depth (negative outside: minus the distance to the surface).
bool fromDistance(const Eigen::Vector3d& away, double radius_m, double margin, Penetration& out) {
  const double distance = away.norm();
  if (!(distance < radius_m + margin)) return false;
  out.normal = distance > 0 ? Eigen::Vector3d(away / distance) : Eigen::Vector3d::UnitZ();
  out.depth_m = radius_m - distance;
  return true;
}

bool inside(const HalfSpaceShape& s, const Eigen::Vector3d& x, double margin, Penetration& out) {
  const double length = s.normal.norm();
  const double signed_distance = (s.normal.dot(x) - s.offset_m) / length;
  if (!(signed_distance < margin)) return false;
  out.normal = s.normal / length;
  out.depth_m = -signed_distance;
  return true;
}

bool inside(const SphereShape& s, const Eigen::Vector3d& x, double margin, Penetration& out) {
  return fromDistance(x - s.centre_m, s.radius_m, margin, out);
}

bool inside(const BoxShape& s, const Eigen::Vector3d& x, double margin, Penetration& out) {
  const Eigen::Vector3d local = s.axes.transpose() * (x - s.centre_m);
  const Eigen::Vector3d room = s.half_extents_m - local.cwiseAbs();  // distance to each face pair
  Eigen::Index axis = 0;
  const double least = room.minCoeff(&axis);  // inside: the nearest face; outside: the face it is beyond
  if (!(least > -margin)) return false;
  out.depth_m = least;  // outside near an edge this overestimates the distance: harmless within a margin
  out.normal = s.axes.col(axis) * (local[axis] < 0 ? -1.0 : 1.0);
  return true;
}

bool inside(const CapsuleShape& s, const Eigen::Vector3d& x, double margin, Penetration& out) {
  const Eigen::Vector3d ab = s.b_m - s.a_m;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((x - s.a_m).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return fromDistance(x - (s.a_m + t * ab), s.radius_m, margin, out);
}

/// The cylinder's unit axis, a to b (up for a cylinder of no length).
Eigen::Vector3d axisOf(const CylinderShape& s) {
  const Eigen::Vector3d along = s.b_m - s.a_m;
  const double length = along.norm();
  return length > 0 ? Eigen::Vector3d(along / length) : Eigen::Vector3d::UnitZ();
}

/// The cylinder's cross-section swept along the sweep's part across the axis `u`.
Eigen::Vector3d sweepAcross(const CylinderShape& s, const Eigen::Vector3d& u) {
  return s.sweep_m - u.dot(s.sweep_m) * u;
}

bool inside(const CylinderShape& s, const Eigen::Vector3d& x, double margin, Penetration& out) {
  const Eigen::Vector3d u = axisOf(s);
  const double length = (s.b_m - s.a_m).norm();
  const double t = u.dot(x - s.a_m);                   // along the axis, from a
  const Eigen::Vector3d across = (x - s.a_m) - t * u;  // from the axis, across it
  const Eigen::Vector3d sweep = sweepAcross(s, u);
  const double sweep2 = sweep.squaredNorm();
  const double on_sweep = sweep2 > 0 ? std::clamp(across.dot(sweep) / sweep2, 0.0, 1.0) : 0.0;
  const Eigen::Vector3d radial = across - on_sweep * sweep;  // from the swept axis
  const double distance = radial.norm();
  Eigen::Vector3d radial_unit;
  if (distance > 0) {
    radial_unit = radial / distance;
  } else {  // on the axis: back against the sweep (toward the car), else any direction across
    const Eigen::Vector3d fallback = sweep2 > 0 ? Eigen::Vector3d(-sweep) : u.unitOrthogonal();
    radial_unit = fallback.normalized();
  }
  const double radial_excess = distance - s.radius_m;    // > 0 outside the side
  const double axial_excess = std::max(-t, t - length);  // > 0 beyond an end
  if (s.across_only) {                                   // out through the side only; nothing beyond an end
    if (axial_excess > 0 || !(radial_excess < margin)) return false;
    out.normal = radial_unit;
    out.depth_m = -radial_excess;
    return true;
  }
  const Eigen::Vector3d axial_unit = t < 0.5 * length ? Eigen::Vector3d(-u) : u;
  if (radial_excess <= 0 && axial_excess <= 0) {  // inside: out through the nearer surface
    if (-radial_excess <= -axial_excess) {
      out.normal = radial_unit;
      out.depth_m = -radial_excess;
    } else {
      out.normal = axial_unit;
      out.depth_m = -axial_excess;
    }
    return true;
  }
  const double r = std::max(radial_excess, 0.0), e = std::max(axial_excess, 0.0);
  const double gap = std::hypot(r, e);
  if (!(gap < margin)) return false;
  out.normal = (r * radial_unit + e * axial_unit).normalized();
  out.depth_m = -gap;
  return true;
}

// libccd glue: the obstacle is object 1, the control point inflated to a ball of radius `margin` (a
// point when 0) is object 2.
struct PointObject {
  Eigen::Vector3d point;
  double radius;
};

void toCcd(const Eigen::Vector3d& v, ccd_vec3_t* out) {
  ccdVec3Set(out, v.x(), v.y(), v.z());
}

void supportOfShape(const void* object, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* shape = static_cast<const ConvexSupportShape*>(object);
  toCcd(shape->support(shape->user, Eigen::Vector3d(ccdVec3X(dir), ccdVec3Y(dir), ccdVec3Z(dir))), out);
}
void centreOfShape(const void* object, ccd_vec3_t* out) {
  toCcd(static_cast<const ConvexSupportShape*>(object)->centre_m, out);
}
void supportOfPoint(const void* object, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* ball = static_cast<const PointObject*>(object);
  const Eigen::Vector3d d(ccdVec3X(dir), ccdVec3Y(dir), ccdVec3Z(dir));
  const double length = d.norm();
  toCcd(length > 0 ? Eigen::Vector3d(ball->point + d * (ball->radius / length)) : ball->point, out);
}
void centreOfPoint(const void* object, ccd_vec3_t* out) {
  toCcd(static_cast<const PointObject*>(object)->point, out);
}

bool inside(const ConvexSupportShape& s, const Eigen::Vector3d& x, double margin, Penetration& out) {
  const double reach = s.bounding_radius_m + margin;
  if ((x - s.centre_m).squaredNorm() > reach * reach) return false;  // broad phase
  if (outsideBox(s, x, x, margin)) return false;
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = supportOfShape;
  ccd.center1 = centreOfShape;
  ccd.support2 = supportOfPoint;
  ccd.center2 = centreOfPoint;
  ccd.max_iterations = 100;
  ccd.mpr_tolerance = 1e-9;
  const PointObject point{x, margin};
  ccd_real_t depth = 0;
  ccd_vec3_t dir, pos;
  // "Computes penetration of obj2 into obj1": translating obj2 by depth along dir separates them.
  if (ccdMPRPenetration(&s, &point, &ccd, &depth, &dir, &pos) != 0) return false;
  const Eigen::Vector3d normal(ccdVec3X(&dir), ccdVec3Y(&dir), ccdVec3Z(&dir));
  if (!(depth > 0) || !std::isfinite(depth) || !normal.allFinite() || normal.squaredNorm() == 0) return false;
  out.normal = normal.normalized();
  out.depth_m = depth - margin;  // the ball's penetration less its radius: the point's
  return true;
}

}  // namespace

bool acrossAxis(const Eigen::Vector3d& normal, const Eigen::Vector3d& axis, Eigen::Vector3d& out) {
  constexpr double kLeastAcross = 0.5;  // sin 30 degrees
  const Eigen::Vector3d across = normal - normal.dot(axis) * axis;
  if (!(across.norm() >= kLeastAcross)) return false;
  out = across.normalized();
  return true;
}

bool distanceIsLipschitz(const ContactShape& shape) {
  if (std::holds_alternative<SphereShape>(shape) || std::holds_alternative<CapsuleShape>(shape) ||
      std::holds_alternative<CylinderShape>(shape))
    return true;
  if (const auto* box = std::get_if<BoxShape>(&shape))
    return (box->axes.transpose() * box->axes - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9;
  return false;
}

bool penetration(const ContactShape& shape, const Eigen::Vector3d& point_m, Penetration& out,
                 double margin_m) {
  return std::visit([&](const auto& s) { return inside(s, point_m, margin_m, out); }, shape);
}

SurelyApart::SurelyApart(const ContactShape& shape, double margin_m) {
  constexpr double kSpare = 1 + 1e-9;
  if (const auto* plane = std::get_if<HalfSpaceShape>(&shape)) {
    kind_ = Kind::Plane;
    normal_or_centre_ = plane->normal;
    offset_m_ = plane->offset_m;
    limit_ = margin_m * plane->normal.norm() * kSpare;
    return;
  }
  if (std::holds_alternative<ConvexSupportShape>(shape)) return;
  // A box's test measures along its axes (axes^T (x - c)): with axes that are not orthonormal it holds
  // points far outside its circumsphere (sheared axes), and with axes a float rotation left 4e-8 off unit
  // length, points a hair outside it. The first are never called apart; the second get 1e-5 to spare.
  if (const auto* box = std::get_if<BoxShape>(&shape);
      box &&
      !((box->axes.transpose() * box->axes - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-6))
    return;
  double radius_m = 0;
  if (!boundingSphere(shape, normal_or_centre_, radius_m)) return;
  kind_ = Kind::Ball;
  const double reach_m = (radius_m + 2 * margin_m) * (1 + 1e-5) + 1e-9;
  limit_ = reach_m * reach_m;
}

ConvexPoints::ConvexPoints(std::vector<Eigen::Vector3d> points_m) : points_m_(std::move(points_m)) {
  if (points_m_.empty()) throw InputError("convex shape: no points");
  for (const auto& p : points_m_) {
    if (!p.allFinite()) throw InputError("convex shape: a point is not finite");
    centre_m_ += p;
  }
  centre_m_ /= static_cast<double>(points_m_.size());
  double radius2 = 0;
  for (const auto& p : points_m_) radius2 = std::max(radius2, (p - centre_m_).squaredNorm());
  radius_m_ = std::sqrt(radius2);
}

ConvexSupportShape ConvexPoints::shape() const {
  ConvexSupportShape shape{&ConvexPoints::support, this, centre_m_, radius_m_};
  boundingBox(shape);
  return shape;
}

void boundingBox(ConvexSupportShape& shape) {
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d axis = Eigen::Vector3d::Unit(k);
    shape.box_max_m[k] = shape.support(shape.user, axis)[k];
    shape.box_min_m[k] = shape.support(shape.user, -axis)[k];
  }
}

bool outsideBox(const ConvexSupportShape& shape, const Eigen::Vector3d& low_m, const Eigen::Vector3d& high_m,
                double margin_m) {
  if (!(shape.box_min_m.array() <= shape.box_max_m.array()).all()) return false;  // unknown
  return (high_m.array() < shape.box_min_m.array() - margin_m).any() ||
         (low_m.array() > shape.box_max_m.array() + margin_m).any();
}

Eigen::Vector3d ConvexPoints::support(const void* user, const Eigen::Vector3d& direction) {
  const auto& points = static_cast<const ConvexPoints*>(user)->points_m_;
  return points[farthestAlong(points.data(), points.size(), direction, true)];
}

void checkContactShape(const ContactShape& shape, const char* field_name) {
  const std::string field = field_name;
  std::visit(
      [&field](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, HalfSpaceShape>) {
          detail::requireFinite(s.normal, field + ".normal");
          if (!(s.normal.norm() > 0)) throw InputError(field + ".normal: zero");
          if (!std::isfinite(s.offset_m)) throw InputError(field + ".offset_m: not finite");
        } else if constexpr (std::is_same_v<T, SphereShape>) {
          detail::requireFinite(s.centre_m, field + ".centre_m");
          detail::requireNonNegative(s.radius_m, field + ".radius_m");
        } else if constexpr (std::is_same_v<T, BoxShape>) {
          detail::requireFinite(s.centre_m, field + ".centre_m");
          if (!s.axes.allFinite()) throw InputError(field + ".axes: not finite");
          for (int k = 0; k < 3; ++k)
            detail::requireNonNegative(s.half_extents_m[k], field + ".half_extents_m");
        } else if constexpr (std::is_same_v<T, CapsuleShape>) {
          detail::requireFinite(s.a_m, field + ".a_m");
          detail::requireFinite(s.b_m, field + ".b_m");
          detail::requireNonNegative(s.radius_m, field + ".radius_m");
        } else if constexpr (std::is_same_v<T, CylinderShape>) {
          detail::requireFinite(s.a_m, field + ".a_m");
          detail::requireFinite(s.b_m, field + ".b_m");
          detail::requireFinite(s.sweep_m, field + ".sweep_m");
          detail::requireNonNegative(s.radius_m, field + ".radius_m");
        } else {
          if (!s.support) throw InputError(field + ".support: missing");
          detail::requireFinite(s.centre_m, field + ".centre_m");
          if ((s.box_min_m.array() <= s.box_max_m.array()).all()) {
            detail::requireFinite(s.box_min_m, field + ".box_min_m");
            detail::requireFinite(s.box_max_m, field + ".box_max_m");
          }
          detail::requireNonNegative(s.bounding_radius_m, field + ".bounding_radius_m");
        }
      },
      shape);
}

void bisectSurface(const ContactShape& shape, Eigen::Vector3d& outside_m, Eigen::Vector3d& inside_m,
                   int bisections) {
  Penetration probe;
  for (int k = 0; k < bisections; ++k) {
    const Eigen::Vector3d middle = 0.5 * (outside_m + inside_m);
    (penetration(shape, middle, probe) && probe.depth_m > 0 ? inside_m : outside_m) = middle;
  }
}

bool supportPoint(const ContactShape& shape, const Eigen::Vector3d& direction, Eigen::Vector3d& out_m) {
  const double length = direction.norm();
  const Eigen::Vector3d unit = length > 0 ? Eigen::Vector3d(direction / length) : Eigen::Vector3d::UnitZ();
  if (const auto* sphere = std::get_if<SphereShape>(&shape)) {
    out_m = sphere->centre_m + sphere->radius_m * unit;
  } else if (const auto* box = std::get_if<BoxShape>(&shape)) {
    out_m = box->centre_m;
    for (int k = 0; k < 3; ++k)
      out_m += box->axes.col(k) * (box->axes.col(k).dot(unit) >= 0 ? 1.0 : -1.0) * box->half_extents_m[k];
  } else if (const auto* capsule = std::get_if<CapsuleShape>(&shape)) {
    out_m = (capsule->a_m.dot(unit) >= capsule->b_m.dot(unit) ? capsule->a_m : capsule->b_m) +
            capsule->radius_m * unit;
  } else if (const auto* cylinder = std::get_if<CylinderShape>(&shape)) {
    const Eigen::Vector3d u = axisOf(*cylinder);
    const Eigen::Vector3d across = unit - u.dot(unit) * u;
    const double across_length = across.norm();
    const Eigen::Vector3d sweep = sweepAcross(*cylinder, u);
    out_m = (u.dot(unit) >= 0 ? cylinder->b_m : cylinder->a_m) +
            (across_length > 1e-12 ? Eigen::Vector3d(cylinder->radius_m / across_length * across)
                                   : Eigen::Vector3d::Zero()) +
            (sweep.dot(unit) > 0 ? sweep : Eigen::Vector3d::Zero());
  } else if (const auto* convex = std::get_if<ConvexSupportShape>(&shape)) {
    out_m = convex->support(convex->user, unit);
  } else {
    return false;  // half-space
  }
  return true;
}

bool boundingSphere(const ContactShape& shape, Eigen::Vector3d& centre_m, double& radius_m) {
  if (const auto* sphere = std::get_if<SphereShape>(&shape)) {
    centre_m = sphere->centre_m;
    radius_m = sphere->radius_m;
  } else if (const auto* box = std::get_if<BoxShape>(&shape)) {
    centre_m = box->centre_m;
    radius_m = box->half_extents_m.norm();
  } else if (const auto* capsule = std::get_if<CapsuleShape>(&shape)) {
    centre_m = 0.5 * (capsule->a_m + capsule->b_m);
    radius_m = 0.5 * (capsule->b_m - capsule->a_m).norm() + capsule->radius_m;
  } else if (const auto* cylinder = std::get_if<CylinderShape>(&shape)) {
    const Eigen::Vector3d sweep = sweepAcross(*cylinder, axisOf(*cylinder));
    centre_m = 0.5 * (cylinder->a_m + cylinder->b_m + sweep);
    radius_m =
        std::hypot(0.5 * (cylinder->b_m - cylinder->a_m).norm(), cylinder->radius_m) + 0.5 * sweep.norm();
  } else if (const auto* convex = std::get_if<ConvexSupportShape>(&shape)) {
    centre_m = convex->centre_m;
    radius_m = convex->bounding_radius_m;
  } else {
    return false;
  }
  return true;
}

}  // namespace deform
