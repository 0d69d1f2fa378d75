// Building a scene's world (scene_world.hpp).
#include "scene_world.hpp"

#include <deform/builtin_meshes.hpp>
#include <vehicle/vehicle_settings.hpp>

#include <cstdio>
#include <map>
#include <numbers>

namespace scenes::build {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

}  // namespace

std::string vehicleKey(const SceneConfig& scene, std::size_t index) {
  return scene.vehicles.size() == 1 && index == 0 ? std::string("vehicle")
                                                  : "vehicles[" + std::to_string(index) + "]";
}

deform::ImportOptions importOptions(double scale, const std::optional<std::string>& up,
                                    const std::optional<std::string>& forward) {
  deform::ImportOptions options;
  options.scale = scale;
  if (up) options.up = deform::parseAxis(*up, "mesh_up");
  if (forward) options.forward = deform::parseAxis(*forward, "mesh_forward");
  return options;
}

vehicle::ObstacleId addObstacle(vehicle::World& world, const ObstacleConfig& o, const std::string& where) {
  const vehicle::Pose pose = vehicle::Pose::yawed(o.position_m, o.yaw_deg * kDegree);
  switch (o.type) {
    case ObstacleType::Wall:
      return world.addWall(pose, o.size_m, o.friction);
    case ObstacleType::Box:
      if (o.mass_kg <= 0) return world.addWall(pose, o.size_m, o.friction);
      return world.addConvexMesh(deform::makeBox(o.size_m, 100), pose, o.mass_kg, o.friction);
    case ObstacleType::Post:
      return world.addPost(o.position_m, o.radius_m, o.height_m,
                           o.capsule ? vehicle::PostShape::Capsule : vehicle::PostShape::Cylinder,
                           o.friction);
    case ObstacleType::Vegetation:
      return world.addVegetation(o.position_m, o.radius_m, o.height_m, o.mass_kg, o.friction);
    case ObstacleType::Ramp:
      return world.addRamp(pose, o.length_m, o.width_m, o.height_m, o.friction);
    case ObstacleType::Mesh: {
      const deform::VehicleModel mesh = withSource(where + ".mesh", [&] {
        return deform::loadVehicleModel(o.mesh, importOptions(o.mesh_scale, {}, {}));
      });
      return world.addConvexMesh(mesh.body, pose, o.mass_kg, o.friction);
    }
  }
  return 0;
}

vehicle::WorldSettings worldSettings(const SceneConfig& scene, int internal_steps) {
  vehicle::WorldSettings settings;
  settings.physics_rate_hz = scene.physics_hz * internal_steps;
  settings.gravity_mps2 = {0, 0, -scene.gravity_mps2};
  settings.ground = scene.ground;
  settings.ground_friction = scene.ground_friction;
  return settings;
}

std::vector<std::shared_ptr<const deform::VehicleModel>> loadModels(const SceneConfig& scene) {
  std::map<std::string, std::shared_ptr<const deform::VehicleModel>> loaded;
  std::vector<std::shared_ptr<const deform::VehicleModel>> models;
  for (std::size_t i = 0; i < scene.vehicles.size(); ++i) {
    const VehicleConfig& v = scene.vehicles[i];
    char scale[40];
    std::snprintf(scale, sizeof scale, "%a", v.mesh_scale);  // exact
    const std::string key =
        v.mesh + "\n" + scale + "\n" + v.mesh_up.value_or("") + "\n" + v.mesh_forward.value_or("");
    std::shared_ptr<const deform::VehicleModel>& shared = loaded[key];
    if (!shared) {
      shared = withSource(scene.source + ": " + vehicleKey(scene, i) + ".mesh", [&] {
        return std::make_shared<const deform::VehicleModel>(
            deform::loadVehicleModel(v.mesh, importOptions(v.mesh_scale, v.mesh_up, v.mesh_forward)));
      });
    }
    models.push_back(shared);
  }
  return models;
}

vehicle::VehicleSettings carSettings(const VehicleConfig& v, const deform::VehicleModel& model,
                                     const std::string& where) {
  vehicle::VehicleSettings base;
  base.collision_points = v.collision_points;
  base.wheels = vehicle::wheelsFromModel(base, model);
  if (v.wheels_in_body && model.wheels.empty()) {
    // Modelled wheels are part of the body: tyres touching down at the mesh's bottom (plus 1 %).
    const deform::Aabb box = deform::boundingBox(model.body);
    for (vehicle::WheelSettings& w : base.wheels) {
      w.centre_m.z() = box.min_m.z() + w.radius_m + 0.01 * box.size_m().z();
    }
  }
  return withSource(where + ".mass_kg", [&] { return vehicle::settingsForMass(base, v.mass_kg); });
}

vehicle::CarStart carStart(const VehicleConfig& v) {
  vehicle::CarStart start;
  start.position_m = v.start.position_m;
  start.heading_rad = v.start.heading_deg * kDegree;
  start.speed_mps = v.start.speed_kmh / 3.6;
  start.on_ground = v.start.on_ground;
  return start;
}

void driveCar(vehicle::World& world, vehicle::CarId id, const vehicle::DriverInput& input,
              double lateral_speed_mps) {
  vehicle::Car& chassis = world.car(id);
  chassis.setInput(input);
  if (world.stepCount() == 0 && lateral_speed_mps != 0) {
    const vehicle::Pose body = chassis.bodyPose();
    const Eigen::Vector3d left = body.orientation * Eigen::Vector3d::UnitY();
    world.addForce({vehicle::EntityRef::Kind::Car, id},
                   chassis.mass_kg() * lateral_speed_mps / world.fixedDt_s() * left, body.position_m);
  }
}

}  // namespace scenes::build
