// Building a deformable car's shared part once (car_build.hpp).
#include <vehicle/car_build.hpp>
#include <vehicle/material_map.hpp>
#include <vehicle/world.hpp>

#include <cstring>

namespace vehicle {
namespace {

std::vector<Eigen::Vector3d> bodyPoints(const deform::VehicleModel& model) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(model.body.positions_m.size());
  for (const auto& p : model.body.positions_m) points.push_back(p.cast<double>());
  return points;
}

// Appends a value's bytes to a key (plain numbers only: no padding, no pointers).
template <typename T>
void put(std::string& key, const T& value) {
  static_assert(std::is_arithmetic_v<T>);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  key.append(bytes, sizeof(T));
}

void put(std::string& key, const std::string& text) {
  put(key, text.size());
  key += text;
}

void put(std::string& key, const deform::Aabb& box) {
  for (int i = 0; i < 3; ++i) put(key, box.min_m[i]);
  for (int i = 0; i < 3; ++i) put(key, box.max_m[i]);
}

void put(std::string& key, const deform::Material& material) {
  // Every member shapes the body: the whole struct (doubles only, no padding).
  static_assert(sizeof(deform::Material) % sizeof(double) == 0);
  const auto* values = reinterpret_cast<const double*>(&material);
  for (std::size_t i = 0; i < sizeof(deform::Material) / sizeof(double); ++i) put(key, values[i]);
}

}  // namespace

std::string carBuildKey(const deform::VehicleModel& model, const VehicleSettings& car,
                        const DeformationSettings& deformation) {
  std::string key;
  const auto& positions = model.body.positions_m;
  put(key, positions.size());
  put(key, fnv1a(positions.data(), positions.size() * sizeof(Eigen::Vector3f)));
  put(key, model.source);
  put(key, car.mass_kg);
  put(key, car.collision_points);
  put(key, deformation.control_points);
  put(key, deformation.shell_mass_fraction);
  put(key, deformation.max_deviation_m);
  put(key, deformation.anchored_columns);
  put(key, deformation.material);
  put(key, deformation.regions.size());
  for (const RegionMaterial& region : deformation.regions) {
    put(key, region.name);
    put(key, region.boxes.size());
    for (const deform::Aabb& box : region.boxes) put(key, box);
    put(key, region.values.size());
    for (const auto& [member, value] : region.values) {
      put(key, std::string(member->key));
      put(key, value);
    }
  }
  return key;
}

std::shared_ptr<const CarBuild> buildCar(const deform::VehicleModel& model, const VehicleSettings& car,
                                         const DeformationSettings& deformation) {
  auto build = std::make_shared<CarBuild>();
  const std::vector<Eigen::Vector3d> points = bodyPoints(model);
  const std::string source = model.source.empty() ? "vehicle model" : model.source;
  build->control_mesh = deform::buildControlMesh(points, deformation.control_points, source.c_str());
  build->collision_hull = collisionHull(points, car.collision_points, source.c_str());
  // The shell's share of the car's mass, spread over the points by the tetrahedral fan (its shape only:
  // the points hold shell_mass_fraction of the car); the chassis keeps the rest.
  build->masses = deform::distributeMass(build->control_mesh, car.mass_kg);
  double points_kg = 0;
  for (double m : build->masses.point_mass_kg) points_kg += m;
  build->shell_mass_kg = car.mass_kg * deformation.shell_mass_fraction;
  for (double& m : build->masses.point_mass_kg) m *= build->shell_mass_kg / points_kg;
  build->masses.core_mass_kg = car.mass_kg - build->shell_mass_kg;
  deform::BodyDescription description;
  description.material = deformation.material;
  description.max_deviation_m = deformation.max_deviation_m;
  description.anchored_columns = deformation.anchored_columns;
  build->bounds_m = deform::boundingBox(model.body);
  description.regions = placeMaterialMap(deformation.regions, deformation.material, build->bounds_m);
  build->body_settings = std::make_shared<const deform::BodySettings>(
      deform::createBodySettings(build->control_mesh, build->masses, description));
  build->description = std::move(description);
  return build;
}

std::shared_ptr<const CarBuild> CarBuildCache::get(const deform::VehicleModel& model,
                                                   const VehicleSettings& car,
                                                   const DeformationSettings& deformation) {
  std::string key = carBuildKey(model, car, deformation);
  auto it = builds_.find(key);
  if (it != builds_.end()) return it->second;
  std::shared_ptr<const CarBuild> build = buildCar(model, car, deformation);
  builds_.emplace(std::move(key), build);
  return build;
}

}  // namespace vehicle
