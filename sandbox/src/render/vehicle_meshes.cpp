#include "render/vehicle_meshes.hpp"

#include <cmath>
#include <numbers>

namespace sandbox::render {
namespace {

// A flat disc facing +Y (or -Y) at `y_m` in the wheel frame: the hub cap that makes a plain tyre
// cylinder read as a wheel. Drawn two-sided, so it is not marked closed.
MeshData hubCap(double radius_m, double y_m) {
  constexpr int kSegments = 24;
  const float side = y_m >= 0 ? 1.0f : -1.0f;
  MeshData cap;
  cap.positions_m.emplace_back(0.0f, static_cast<float>(y_m), 0.0f);
  for (int i = 0; i < kSegments; ++i) {
    const double a = 2.0 * std::numbers::pi * i / kSegments;
    cap.positions_m.emplace_back(static_cast<float>(radius_m * std::cos(a)), static_cast<float>(y_m),
                                 static_cast<float>(radius_m * std::sin(a)));
  }
  cap.normals.assign(cap.positions_m.size(), Eigen::Vector3f(0.0f, side, 0.0f));
  for (uint32_t i = 0; i < kSegments; ++i) cap.triangles.push_back({0, 1 + i, 1 + (i + 1) % kSegments});
  cap.base_colour = kHubColour;
  cap.specular = 0.5f;
  cap.shininess = 40.0f;
  return cap;
}

}  // namespace

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
    // Caps a hair outside both side walls (1 mm: clear of depth fighting, invisible as a gap).
    for (const double side : {-1.0, 1.0}) {
      MeshData cap = hubCap(0.55 * wheel.radius_m, side * (wheel.width_m / 2.0 + 0.001));
      cap.model = meshes.back().model;
      meshes.push_back(std::move(cap));
    }
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
