#pragma once
// The immutable part of a deformable car (DESIGN.md sections 4 and 8): its control mesh, masses, body
// settings and collision hull, built once from a mesh and the settings that shape them and shared by every
// car built the same way. Only state (the body's, the chassis's, the coupling's) is per car.
#include <vehicle/simulation.hpp>
#include <vehicle/vehicle_settings.hpp>

#include <deform/body_settings.hpp>
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/masses.hpp>
#include <deform/mesh.hpp>

#include <map>
#include <memory>
#include <string>

namespace vehicle {

struct CarBuild {
  deform::ControlMesh control_mesh;    ///< the deformable body's rest control mesh (vehicle frame)
  deform::ControlMesh collision_hull;  ///< the chassis's collision hull (VehicleSettings::collision_points)
  /// Point masses carrying shell_mass_fraction of the car; the core (chassis) the rest [kg].
  deform::MassSplit masses;
  double shell_mass_kg = 0;  ///< sum of the point masses [kg]
  deform::Aabb bounds_m;     ///< the model's body mesh [m]
  std::shared_ptr<const deform::BodySettings> body_settings;
  deform::BodyDescription description;  ///< what body_settings was built with (a refinement builds again)
};

/// Builds it from `model`'s body (two convex hulls, the mass fan, the constraints): the costly part of
/// adding a car. Throws deform::InputError for a mesh the control mesh refuses.
std::shared_ptr<const CarBuild> buildCar(const deform::VehicleModel& model, const VehicleSettings& car,
                                         const DeformationSettings& deformation);

/// Bytes equal for two (model, car, deformation) that buildCar turns into the same build: a hash of the
/// body mesh's vertices and triangles, its source, and every setting buildCar reads (mass, collision
/// points, control points, shell mass fraction, material, regions, visual constraint, anchored columns).
std::string carBuildKey(const deform::VehicleModel& model, const VehicleSettings& car,
                        const DeformationSettings& deformation);

/// Builds by carBuildKey: the second car with the same mesh and shaping settings takes the first's.
class CarBuildCache {
 public:
  std::shared_ptr<const CarBuild> get(const deform::VehicleModel& model, const VehicleSettings& car,
                                      const DeformationSettings& deformation);
  std::size_t size() const { return builds_.size(); }  ///< distinct builds made

 private:
  std::map<std::string, std::shared_ptr<const CarBuild>> builds_;
};

}  // namespace vehicle
