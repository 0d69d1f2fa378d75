// The obstacles a car's render mesh is kept out of (skin_obstacles.hpp).
#include <scenes/skin_obstacles.hpp>

#include <deform/surface_projection.hpp>

namespace scenes {

void SkinObstacles::gather(const vehicle::Simulation& simulation, vehicle::CarId id,
                           const deform::Aabb& rest_box_m, double reach_m) {
  hulls_.clear();
  shapes_.clear();
  const vehicle::World& world = simulation.world();
  const vehicle::Pose frame = world.car(id).vehiclePose();
  for (std::size_t o = 0; o < world.obstacleCount(); ++o)
    add(vehicle::transformShape(world.obstacleShape(static_cast<vehicle::ObstacleId>(o)), frame), rest_box_m,
        reach_m);
  for (std::size_t c = 0; c < world.carCount(); ++c) {
    const auto other = static_cast<vehicle::CarId>(c);
    if (other == id) continue;
    if (!simulation.isDeformable(other)) {
      add(vehicle::transformShape(world.shapeOf({vehicle::EntityRef::Kind::Car, other}), frame), rest_box_m,
          reach_m);
      continue;
    }
    const vehicle::Pose other_frame = world.car(other).vehiclePose();
    vehicle::ObstacleShape hull;
    hull.type = vehicle::ShapeType::Convex;
    for (const Eigen::Vector3d& p : simulation.controlPoints(other))
      hull.vertices_m.push_back(frame.toLocal(other_frame.toWorld(p)));
    add(hull, rest_box_m, reach_m);
  }
}

void SkinObstacles::add(const vehicle::ObstacleShape& shape, const deform::Aabb& rest_box_m, double reach_m) {
  deform::ContactShape contact;
  switch (shape.type) {
    case vehicle::ShapeType::HalfSpace:
      contact = deform::HalfSpaceShape{shape.normal, shape.offset_m};
      break;
    case vehicle::ShapeType::Sphere:
      contact = deform::SphereShape{shape.centre_m, shape.radius_m};
      break;
    case vehicle::ShapeType::Box:
      contact = deform::BoxShape{shape.centre_m, shape.axes, shape.half_extents_m};
      break;
    case vehicle::ShapeType::Capsule:
      contact = deform::CapsuleShape{shape.a_m, shape.b_m, shape.radius_m};
      break;
    case vehicle::ShapeType::Cylinder:  // flat ends: a post's top is not rounded
      contact = deform::CylinderShape{shape.a_m, shape.b_m, shape.radius_m, Eigen::Vector3d::Zero()};
      break;
    case vehicle::ShapeType::Convex: {
      if (shape.vertices_m.empty()) return;
      hulls_.push_back(std::make_unique<deform::ConvexPoints>(shape.vertices_m));
      contact = hulls_.back()->shape();
      break;
    }
  }
  deform::Aabb near;
  if (!deform::shapeBounds(contact, rest_box_m, reach_m, near)) {
    if (shape.type == vehicle::ShapeType::Convex) hulls_.pop_back();
    return;
  }
  shapes_.push_back(contact);
}

}  // namespace scenes
