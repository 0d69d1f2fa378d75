// Support functions of the obstacle shapes (exact), and their change of frame.
#include <vehicle/obstacle_shape.hpp>

#include <cassert>
#include <cmath>
#include <limits>

namespace vehicle {
namespace {

Eigen::Vector3d unitOr(const Eigen::Vector3d& v, const Eigen::Vector3d& fallback) {
  const double n = v.norm();
  return n > 1e-300 ? Eigen::Vector3d(v / n) : fallback;
}

}  // namespace

Eigen::Vector3d supportPoint(const ObstacleShape& shape, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d d = unitOr(direction, Eigen::Vector3d::UnitX());
  switch (shape.type) {
    case ShapeType::HalfSpace:
      assert(false && "a half-space has no support point");
      return Eigen::Vector3d::Zero();
    case ShapeType::Sphere:
      return shape.centre_m + shape.radius_m * d;
    case ShapeType::Box: {
      Eigen::Vector3d p = shape.centre_m;
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d axis = shape.axes.col(i);
        p += (axis.dot(d) >= 0 ? 1.0 : -1.0) * shape.half_extents_m[i] * axis;
      }
      return p;
    }
    case ShapeType::Capsule:
      return ((shape.b_m - shape.a_m).dot(d) >= 0 ? shape.b_m : shape.a_m) + shape.radius_m * d;
    case ShapeType::Cylinder: {
      const Eigen::Vector3d axis = unitOr(shape.b_m - shape.a_m, Eigen::Vector3d::UnitZ());
      const Eigen::Vector3d end = axis.dot(d) >= 0 ? shape.b_m : shape.a_m;
      const Eigen::Vector3d radial = d - axis.dot(d) * axis;
      const double length = radial.norm();
      return length > 1e-12 ? Eigen::Vector3d(end + shape.radius_m * radial / length) : end;
    }
    case ShapeType::Convex: {
      assert(!shape.vertices_m.empty());
      std::size_t best = 0;
      double best_dot = -std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < shape.vertices_m.size(); ++i) {
        const double dot = shape.vertices_m[i].dot(d);
        if (dot > best_dot) {
          best_dot = dot;
          best = i;
        }
      }
      return shape.vertices_m[best];
    }
  }
  return shape.centre_m;
}

Eigen::Vector3d interiorPoint(const ObstacleShape& shape) {
  switch (shape.type) {
    case ShapeType::HalfSpace:
      return shape.normal * (shape.offset_m - 1.0);
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
      return 0.5 * (shape.a_m + shape.b_m);
    default:
      return shape.centre_m;
  }
}

double boundingRadius(const ObstacleShape& shape) {
  switch (shape.type) {
    case ShapeType::HalfSpace:
      return std::numeric_limits<double>::infinity();
    case ShapeType::Sphere:
      return shape.radius_m;
    case ShapeType::Box:
      return shape.half_extents_m.norm();
    case ShapeType::Capsule:
      return 0.5 * (shape.b_m - shape.a_m).norm() + shape.radius_m;
    case ShapeType::Cylinder:
      return std::hypot(0.5 * (shape.b_m - shape.a_m).norm(), shape.radius_m);
    case ShapeType::Convex: {
      double r = 0;
      for (const auto& v : shape.vertices_m) r = std::max(r, (v - shape.centre_m).norm());
      return r;
    }
  }
  return 0;
}

ObstacleShape transformShape(const ObstacleShape& shape, const Pose& frame) {
  ObstacleShape out = shape;
  const Eigen::Matrix3d to_frame = frame.orientation.conjugate().toRotationMatrix();
  out.normal = to_frame * shape.normal;
  out.offset_m = shape.offset_m - shape.normal.dot(frame.position_m);
  out.centre_m = frame.toLocal(shape.centre_m);
  out.axes = to_frame * shape.axes;
  out.a_m = frame.toLocal(shape.a_m);
  out.b_m = frame.toLocal(shape.b_m);
  for (auto& v : out.vertices_m) v = frame.toLocal(v);
  return out;
}

}  // namespace vehicle
