// Obstacles as deform contact shapes, swept along the relative motion (crush_shapes.hpp).
#include "crush_shapes.hpp"

#include <cmath>

namespace vehicle {

Eigen::Vector3d SweptShape::support(const void* user, const Eigen::Vector3d& direction) {
  const auto& self = *static_cast<const SweptShape*>(user);
  Eigen::Vector3d p = supportPoint(self.shape, direction);
  if (direction.dot(self.sweep_m) > 0) p += self.sweep_m;
  if (direction.dot(self.down_m) > 0) p += self.down_m;
  return p;
}

void CrushShapes::clear() {
  swept_.clear();
  shapes_.clear();
  surface_.clear();
  exact_.clear();
}

namespace {

/// A post (cylinder or capsule) as the box around it whose first axis faces along the sweep: its push-out
/// is exact, to the nearest face. libccd's MPR on the support function pushes a point out along the ray
/// from the shape's interior point through it, not to the nearest surface; extended 2 m into the ground,
/// a post's interior point lies a metre underground, so a point a few centimetres inside the post at
/// bumper height left through the top (measured: a bonnet point thrown 1 m up by a 0.1 m bollard at
/// 13 km/h). The box has the post's width across the sweep, so its near face is the post's nearest point
/// for a point straight ahead, and a point beside the axis is pushed sideways or back, never over the top.
ObstacleShape postBox(const ObstacleShape& post, const Eigen::Vector3d& sweep_m) {
  const Eigen::Vector3d along = post.b_m - post.a_m;
  const double length = along.norm();
  const Eigen::Vector3d axis = length > 1e-12 ? Eigen::Vector3d(along / length) : Eigen::Vector3d::UnitZ();
  Eigen::Vector3d facing = sweep_m - axis.dot(sweep_m) * axis;
  if (facing.norm() < 1e-9) facing = Eigen::Vector3d::UnitX() - axis.x() * axis;
  if (facing.norm() < 1e-9) facing = Eigen::Vector3d::UnitY() - axis.y() * axis;
  facing.normalize();
  ObstacleShape box;
  box.type = ShapeType::Box;
  box.centre_m = 0.5 * (post.a_m + post.b_m);
  box.axes.col(0) = facing;
  box.axes.col(1) = axis.cross(facing);
  box.axes.col(2) = axis;
  const double half_length = 0.5 * length + (post.type == ShapeType::Capsule ? post.radius_m : 0.0);
  box.half_extents_m = {post.radius_m, post.radius_m, half_length};
  return box;
}

}  // namespace

void CrushShapes::add(const ObstacleShape& shape, const Eigen::Vector3d& sweep_m,
                      const Eigen::Vector3d& down_m, bool post, bool surface) {
  if (post && (shape.type == ShapeType::Cylinder || shape.type == ShapeType::Capsule)) {
    // The extended shape is the box around the post (exact push-out); what is left inside is measured
    // against the post itself.
    const std::size_t exact_before = exact_.size();
    add(postBox(shape, sweep_m), sweep_m, down_m, false, surface);
    exact_.resize(exact_before);
    auto plain = std::make_unique<SweptShape>();
    plain->shape = shape;
    deform::ConvexSupportShape support;
    support.support = &SweptShape::support;
    support.user = plain.get();
    support.centre_m = interiorPoint(shape);
    support.bounding_radius_m = boundingRadius(shape);
    exact_.push_back(support);
    swept_.push_back(std::move(plain));
    return;
  }
  switch (shape.type) {
    case ShapeType::HalfSpace:
      shapes_.push_back(deform::HalfSpaceShape{shape.normal, shape.offset_m});
      surface_.push_back(surface);
      exact_.push_back(shapes_.back());
      return;
    case ShapeType::Box: {
      // Extend the box along its axis closest to each extension, on that side only.
      deform::BoxShape box{shape.centre_m, shape.axes, shape.half_extents_m};
      exact_.push_back(box);
      for (const Eigen::Vector3d& extension : {sweep_m, down_m}) {
        int axis = 0;
        double best = -1;
        for (int i = 0; i < 3; ++i) {
          const double along = std::abs(shape.axes.col(i).dot(extension));
          if (along > best) {
            best = along;
            axis = i;
          }
        }
        const Eigen::Vector3d a = shape.axes.col(axis);
        const double extra = std::abs(a.dot(extension));
        box.half_extents_m[axis] += 0.5 * extra;
        box.centre_m += (a.dot(extension) >= 0 ? 0.5 : -0.5) * extra * a;
      }
      shapes_.push_back(box);
      surface_.push_back(surface);
      return;
    }
    default: {
      auto swept = std::make_unique<SweptShape>();
      swept->shape = shape;
      swept->sweep_m = sweep_m;
      swept->down_m = down_m;
      deform::ConvexSupportShape support;
      support.support = &SweptShape::support;
      support.user = swept.get();
      support.centre_m = interiorPoint(shape) + 0.5 * (sweep_m + down_m);
      support.bounding_radius_m = boundingRadius(shape) + sweep_m.norm() + down_m.norm();
      shapes_.push_back(support);
      surface_.push_back(surface);
      swept_.push_back(std::move(swept));
      auto plain = std::make_unique<SweptShape>();
      plain->shape = shape;
      support.user = plain.get();
      support.centre_m = interiorPoint(shape);
      support.bounding_radius_m = boundingRadius(shape);
      exact_.push_back(support);
      swept_.push_back(std::move(plain));
      return;
    }
  }
}

}  // namespace vehicle
