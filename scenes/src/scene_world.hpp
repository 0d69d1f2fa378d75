#pragma once
// Building a scene's world (scene_run.cpp and the budget's rehearsal, contact_rehearsal.cpp): obstacles,
// car settings and starts from the scene file, and messages naming the file and key.
#include <scenes/scene.hpp>

#include <deform/error.hpp>
#include <deform/mesh_import.hpp>
#include <vehicle/world.hpp>

#include <memory>
#include <string>
#include <vector>

namespace scenes::build {

/// The scene file's name for vehicle `index` (its key path), for messages.
std::string vehicleKey(const SceneConfig& scene, std::size_t index);

/// Re-throws an InputError from the vehicle or mesh side with the scene file and key path in front.
template <typename F>
auto withSource(const std::string& where, F&& f) {
  try {
    return f();
  } catch (const deform::InputError& e) {
    throw deform::InputError(where + ": " + e.what());
  }
}

deform::ImportOptions importOptions(double scale, const std::optional<std::string>& up,
                                    const std::optional<std::string>& forward);

/// The world of `scene` stepped `internal_steps` times per physics step (gravity, ground).
vehicle::WorldSettings worldSettings(const SceneConfig& scene, int internal_steps);

/// Every vehicle's model, one per vehicle in order; vehicles with the same mesh spec (mesh, scale, axes)
/// share one loaded model (DESIGN.md section 8). Messages name the file and the vehicle's mesh key.
std::vector<std::shared_ptr<const deform::VehicleModel>> loadModels(const SceneConfig& scene);

/// Obstacle `o` added to `world`; `where` names it in messages (its mesh, for a mesh obstacle).
vehicle::ObstacleId addObstacle(vehicle::World& world, const ObstacleConfig& o, const std::string& where);

/// Car `v`'s settings for `model`: wheels from the model (or in its body), suspension, engine and brakes
/// for its mass; `where` names it in messages.
vehicle::VehicleSettings carSettings(const VehicleConfig& v, const deform::VehicleModel& model,
                                     const std::string& where);

/// Car `v`'s start (place, heading, forward speed).
vehicle::CarStart carStart(const VehicleConfig& v);

/// The scripted inputs of car `id` for the step about to be taken, and at the first step a sideways start
/// (a car sliding into a pole: one step's push of m dv / dt at the centre of mass).
void driveCar(vehicle::World& world, vehicle::CarId id, const vehicle::DriverInput& input,
              double lateral_speed_mps);

}  // namespace scenes::build
