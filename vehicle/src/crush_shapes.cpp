// Obstacles as deform contact shapes, swept along the relative motion (crush_shapes.hpp).
#include "crush_shapes.hpp"

#include <cmath>

namespace vehicle {

Eigen::Vector3d SweptShape::support(const void* user, const Eigen::Vector3d& direction) {
  const auto& self = *static_cast<const SweptShape*>(user);
  const Eigen::Vector3d p = supportPoint(self.shape, direction);
  return direction.dot(self.sweep_m) > 0 ? Eigen::Vector3d(p + self.sweep_m) : p;
}

void CrushShapes::clear() {
  swept_.clear();
  shapes_.clear();
}

void CrushShapes::add(const ObstacleShape& shape, const Eigen::Vector3d& sweep_m) {
  switch (shape.type) {
    case ShapeType::HalfSpace:
      shapes_.push_back(deform::HalfSpaceShape{shape.normal, shape.offset_m});
      return;
    case ShapeType::Box: {
      // Extend the box along the axis closest to the sweep, on the far side only.
      int axis = 0;
      double best = -1;
      for (int i = 0; i < 3; ++i) {
        const double along = std::abs(shape.axes.col(i).dot(sweep_m));
        if (along > best) {
          best = along;
          axis = i;
        }
      }
      deform::BoxShape box{shape.centre_m, shape.axes, shape.half_extents_m};
      const Eigen::Vector3d a = shape.axes.col(axis);
      const double extra = std::abs(a.dot(sweep_m));
      box.half_extents_m[axis] += 0.5 * extra;
      box.centre_m += (a.dot(sweep_m) >= 0 ? 0.5 : -0.5) * extra * a;
      shapes_.push_back(box);
      return;
    }
    default: {
      auto swept = std::make_unique<SweptShape>();
      swept->shape = shape;
      swept->sweep_m = sweep_m;
      deform::ConvexSupportShape support;
      support.support = &SweptShape::support;
      support.user = swept.get();
      support.centre_m = interiorPoint(shape) + 0.5 * sweep_m;
      support.bounding_radius_m = boundingRadius(shape) + sweep_m.norm();
      shapes_.push_back(support);
      swept_.push_back(std::move(swept));
      return;
    }
  }
}

}  // namespace vehicle
