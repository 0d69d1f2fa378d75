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
  exact_.clear();
}

void CrushShapes::add(const ObstacleShape& shape, const Eigen::Vector3d& sweep_m,
                      const Eigen::Vector3d& down_m) {
  switch (shape.type) {
    case ShapeType::HalfSpace:
      shapes_.push_back(deform::HalfSpaceShape{shape.normal, shape.offset_m});
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
