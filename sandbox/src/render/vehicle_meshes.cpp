#include "render/vehicle_meshes.hpp"

namespace sandbox::render {

std::vector<MeshData> vehicleMeshes(const deform::VehicleModel& model, const Eigen::Vector3f& body_colour) {
  std::vector<MeshData> meshes;
  meshes.push_back(meshData(model.body, body_colour));
  meshes.back().specular = 0.45f;  // painted metal
  meshes.back().shininess = 80.0f;
  for (const deform::WheelPart& wheel : model.wheels) {
    MeshData tyre = meshData(deform::makeWheelMesh(wheel.radius_m, wheel.width_m), kTyreColour);
    tyre.model.block<3, 1>(0, 3) = wheel.centre_m.cast<float>();
    tyre.specular = 0.08f;  // rubber
    tyre.shininess = 12.0f;
    meshes.push_back(std::move(tyre));
  }
  return meshes;
}

deform::Aabb vehicleBounds(const deform::VehicleModel& model) {
  deform::Aabb box = deform::boundingBox(model.body);
  for (const deform::WheelPart& wheel : model.wheels) {
    const Eigen::Vector3d half(wheel.radius_m, wheel.width_m / 2.0, wheel.radius_m);
    box.min_m = box.min_m.cwiseMin(wheel.centre_m - half);
    box.max_m = box.max_m.cwiseMax(wheel.centre_m + half);
  }
  return box;
}

}  // namespace sandbox::render
