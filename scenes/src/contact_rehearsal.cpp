// The deformation budget's rehearsal (deformation_budget.hpp): the scene played once with rigid cars, to
// find who meets what first along the drive scripts.
#include <scenes/deformation_budget.hpp>
#include <scenes/drive_script.hpp>

#include "scene_world.hpp"

#include <deform/control_mesh.hpp>
#include <vehicle/vehicle_settings.hpp>
#include <vehicle/world.hpp>

#include <map>

namespace scenes {

std::vector<std::shared_ptr<const deform::VehicleModel>> loadVehicleModels(const SceneConfig& scene) {
  return build::loadModels(scene);
}

std::vector<FirstContact> rehearseFirstContacts(
    const SceneConfig& scene, const std::vector<std::shared_ptr<const deform::VehicleModel>>& models,
    int internal_steps, double horizon_s) {
  const std::size_t n = scene.vehicles.size();
  std::vector<FirstContact> first(n);
  if (n == 0 || !(horizon_s > 0)) return first;
  vehicle::World world(build::worldSettings(scene, std::max(internal_steps, 1)));
  std::vector<vehicle::CarId> ids;
  std::vector<DrivePlayer> drivers;
  std::vector<std::size_t> vehicle_of;  // per CarId
  std::map<std::pair<const deform::VehicleModel*, std::size_t>, deform::ControlMesh> hulls;
  for (std::size_t i = 0; i < n; ++i) {
    const VehicleConfig& v = scene.vehicles[i];
    const std::string where = scene.source + ": " + build::vehicleKey(scene, i);
    const deform::VehicleModel& model = *models.at(i);
    const vehicle::VehicleSettings settings = build::carSettings(v, model, where);
    // One collision hull per model and size (as the run's shared CarBuild): the hull of a 20k-vertex
    // mesh costs about 8 ms, 0.3 s for traffic's 41 cars built one by one.
    deform::ControlMesh& hull = hulls[{&model, settings.collision_points}];
    if (hull.points_m.empty()) {
      std::vector<Eigen::Vector3d> points;
      for (const Eigen::Vector3f& p : model.body.positions_m) points.push_back(p.cast<double>());
      const std::string source = model.source.empty() ? "vehicle model" : model.source;
      hull = vehicle::collisionHull(points, settings.collision_points, source.c_str());
    }
    ids.push_back(
        world.addCar(hull, vehicle::wheelsFromModel(settings, model), settings, build::carStart(v)));
    drivers.emplace_back(v.drive);
    vehicle_of.resize(std::max<std::size_t>(vehicle_of.size(), ids.back() + 1), n);
    vehicle_of[ids.back()] = i;
  }
  for (std::size_t i = 0; i < scene.obstacles.size(); ++i) {
    const std::string where = scene.source + ": obstacles[" + std::to_string(i) + "]";
    build::withSource(where, [&] { return build::addObstacle(world, scene.obstacles[i], where); });
  }
  // `self` touched `other` at the end of this step: the first such contact of each car counts.
  std::size_t open = n;
  auto note = [&](const vehicle::EntityRef& self, const vehicle::EntityRef& other) {
    if (self.kind != vehicle::EntityRef::Kind::Car || self.index >= vehicle_of.size()) return;
    FirstContact& f = first[vehicle_of[self.index]];
    if (f.meets != Meets::Nothing) return;
    if (other.kind == vehicle::EntityRef::Kind::Car) {
      f.meets = Meets::Car;
    } else {
      const vehicle::ObstacleKind kind = world.obstacleKind(other.index);
      if (kind == vehicle::ObstacleKind::Ground || kind == vehicle::ObstacleKind::Ramp) return;
      f.meets = Meets::Obstacle;
    }
    f.time_s = world.time_s();
    --open;
  };
  const double dt = world.fixedDt_s();
  while (open > 0 && world.time_s() < horizon_s - 0.5 * dt) {
    for (std::size_t i = 0; i < n; ++i) {
      const vehicle::Car& car = world.car(ids[i]);
      build::driveCar(world, ids[i], drivers[i].inputs(world.time_s(), car.forwardSpeed_mps(), dt),
                      scene.vehicles[i].start.lateral_speed_kmh / 3.6);
    }
    world.step();
    for (const vehicle::ContactPoint& c : world.contacts()) {
      note(c.a, c.b);
      note(c.b, c.a);
    }
  }
  return first;
}

}  // namespace scenes
