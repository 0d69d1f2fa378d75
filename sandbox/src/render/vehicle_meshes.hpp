#pragma once
// A deform::VehicleModel as renderer meshes: the deformable body plus its wheels (drawn, not deformed).
#include "render/scene.hpp"

#include <deform/builtin_meshes.hpp>

#include <vector>

namespace sandbox::render {

/// Paint and tyre colours (sRGB).
inline const Eigen::Vector3f kBodyColour{0.62f, 0.08f, 0.06f};
inline const Eigen::Vector3f kTyreColour{0.07f, 0.07f, 0.075f};
inline const Eigen::Vector3f kHubColour{0.50f, 0.51f, 0.53f};

/// The body first (index 0, coloured `body_colour`), then exactly one mesh per wheel (index 1 + w for
/// model.wheels[w]): a dark tyre with light hub caps (per-vertex colours), in the wheel's own frame (hub
/// at the origin, axle along Y) and placed by its model matrix at the hub, so setting the wheel's pose
/// as the model matrix spins, steers and bounces it. All in the vehicle frame; set MeshData::model to move
/// the car.
std::vector<MeshData> vehicleMeshes(const deform::VehicleModel& model,
                                    const Eigen::Vector3f& body_colour = kBodyColour);

/// Box around the body and the wheels, vehicle frame [m].
deform::Aabb vehicleBounds(const deform::VehicleModel& model);

}  // namespace sandbox::render
