#pragma once
// What a car's render mesh is kept out of this frame (CarSkin::update), as deform's contact shapes in
// its vehicle frame: every obstacle (the ground included) and every other car near it.
#include <vehicle/simulation.hpp>

#include <deform/contact_shapes.hpp>
#include <deform/mesh.hpp>

#include <memory>
#include <vector>

namespace scenes {

class SkinObstacles {
 public:
  /// The obstacles and other cars of `simulation` whose bounding box comes within `reach_m` of
  /// `rest_box_m` (car `id`'s rest mesh, vehicle frame), in car `id`'s vehicle frame now. A deformable
  /// car is the convex hull of its control points now (as the crush coupling meets it: its dented
  /// shape, not its rest hull); a cylinder is the capsule on its axis (rounded past its flat ends by its
  /// radius: above a post's top or under the ground, where a body rarely is).
  void gather(const vehicle::Simulation& simulation, vehicle::CarId id, const deform::Aabb& rest_box_m,
              double reach_m);
  /// Valid until the next gather (the hulls are owned here).
  const std::vector<deform::ContactShape>& shapes() const { return shapes_; }

 private:
  void add(const vehicle::ObstacleShape& shape, const deform::Aabb& rest_box_m, double reach_m);
  std::vector<std::unique_ptr<deform::ConvexPoints>> hulls_;
  std::vector<deform::ContactShape> shapes_;
};

}  // namespace scenes
