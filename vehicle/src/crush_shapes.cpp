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

/// A post (a fixed cylinder or capsule) as deform's cylinder, whose push-out is exact: radially from its
/// axis, never through an end (across_only: the body is cut by a post's top, not carried up it). Extended
/// into the ground by `down_m`'s part along its axis, and across the axis by the sweep (away from the
/// car); a capsule's rounded ends become flat ones at its tips. (It was the box
/// around the post facing the sweep: as the sweep turned with the relative motion, the box turned about the
/// post, and its corners, 41 % further out than the post, came into the control surface from nowhere.)
deform::CylinderShape postCylinder(const ObstacleShape& post, const Eigen::Vector3d& sweep_m,
                                   const Eigen::Vector3d& down_m) {
  const Eigen::Vector3d along = post.b_m - post.a_m;
  const double length = along.norm();
  const Eigen::Vector3d axis = length > 1e-12 ? Eigen::Vector3d(along / length) : Eigen::Vector3d::UnitZ();
  deform::CylinderShape cylinder{post.a_m, post.b_m, post.radius_m, sweep_m, true};
  if (post.type == ShapeType::Capsule) {
    cylinder.a_m -= post.radius_m * axis;
    cylinder.b_m += post.radius_m * axis;
  }
  const double down = axis.dot(down_m);
  (down > 0 ? cylinder.b_m : cylinder.a_m) += down * axis;
  return cylinder;
}

}  // namespace

void CrushShapes::add(const ObstacleShape& shape, const Eigen::Vector3d& sweep_m,
                      const Eigen::Vector3d& down_m, bool post, bool surface) {
  if (post && (shape.type == ShapeType::Cylinder || shape.type == ShapeType::Capsule)) {
    shapes_.push_back(postCylinder(shape, sweep_m, down_m));
    surface_.push_back(surface);
    exact_.push_back(postCylinder(shape, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
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
      deform::boundingBox(support);
      shapes_.push_back(support);
      surface_.push_back(surface);
      swept_.push_back(std::move(swept));
      auto plain = std::make_unique<SweptShape>();
      plain->shape = shape;
      support.user = plain.get();
      support.centre_m = interiorPoint(shape);
      support.bounding_radius_m = boundingRadius(shape);
      deform::boundingBox(support);
      exact_.push_back(support);
      swept_.push_back(std::move(plain));
      return;
    }
  }
}

}  // namespace vehicle
