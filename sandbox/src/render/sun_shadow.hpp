#pragma once
// Fitting the sun's shadow map: an orthographic projection along the sun direction that just covers
// the shadow casters and the patch of ground their shadow falls on, so every texel is spent where a
// shadow can be seen.
#include <Eigen/Geometry>

namespace sandbox::render {

struct SunShadow {
  Eigen::Matrix4f light_view_projection = Eigen::Matrix4f::Identity();  ///< world -> light clip space
  Eigen::Vector2f pcf_radius_uv{0, 0};  ///< PCF kernel radius in shadow-map UV (penumbra width)
  float depth_bias = 0.0f;              ///< constant depth-comparison bias in [0, 1] depth units
  float slope_bias = 0.0f;              ///< extra bias per unit tan(angle to the sun), same units
};

/// Sun shadow for casters inside `casters_m` (world box), a ground plane at `ground_height_m` and the
/// unit direction towards the sun `sun_direction`. `penumbra_m` is the blur radius of shadow edges
/// [m], `map_size` the shadow map's side [texels].
SunShadow fitSunShadow(const Eigen::AlignedBox3f& casters_m, float ground_height_m,
                       const Eigen::Vector3f& sun_direction, float penumbra_m, int map_size);

}  // namespace sandbox::render
