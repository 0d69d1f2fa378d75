#include "render/vehicle_meshes.hpp"

#include <cmath>
#include <numbers>

namespace sandbox::render {
namespace {

// Appends a flat disc facing outwards at `y_m` (wheel frame, axle along Y): the hub cap that makes a
// plain tyre cylinder read as a wheel. Wound counter-clockwise seen from outside, like the tyre.
void appendHubCap(MeshData& wheel, double radius_m, double y_m) {
  constexpr uint32_t kSegments = 24;
  const float side = y_m >= 0 ? 1.0f : -1.0f;
  const auto centre = static_cast<uint32_t>(wheel.positions_m.size());
  wheel.positions_m.emplace_back(0.0f, static_cast<float>(y_m), 0.0f);
  for (uint32_t i = 0; i < kSegments; ++i) {
    const double a = 2.0 * std::numbers::pi * i / kSegments;
    wheel.positions_m.emplace_back(static_cast<float>(radius_m * std::cos(a)), static_cast<float>(y_m),
                                   static_cast<float>(radius_m * std::sin(a)));
  }
  wheel.normals.resize(wheel.positions_m.size(), Eigen::Vector3f(0.0f, side, 0.0f));
  wheel.colours.resize(wheel.positions_m.size(), kHubColour);
  for (uint32_t i = 0; i < kSegments; ++i) {
    // (x, z) = (cos a, sin a) turns from +X towards +Z, which is clockwise seen from +Y.
    const uint32_t a = centre + 1 + i, b = centre + 1 + (i + 1) % kSegments;
    wheel.triangles.push_back(side > 0 ? deform::Triangle{centre, b, a} : deform::Triangle{centre, a, b});
  }
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
    tyre.specular = 0.12f;  // rubber, and a little sheen on the caps
    tyre.shininess = 16.0f;
    tyre.colours.assign(tyre.positions_m.size(), kTyreColour);
    // Caps 1 mm outside both side walls: clear of depth fighting, invisible as a gap. They make the
    // wheel an open surface, so it is drawn two-sided (it is small: that costs nothing).
    for (const double side : {-1.0, 1.0})
      appendHubCap(tyre, 0.55 * wheel.radius_m, side * (wheel.width_m / 2.0 + 0.001));
    tyre.closed = false;
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
