#pragma once
// Small markers drawn into a scene to point at something: a control point in the influence heat map.
#include "render/scene.hpp"

namespace sandbox::render {

/// A sphere of `radius_m` around `centre_m` (world), closed, in `colour` (sRGB).
MeshData markerSphere(const Eigen::Vector3f& centre_m, float radius_m, const Eigen::Vector3f& colour);

}  // namespace sandbox::render
