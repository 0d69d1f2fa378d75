#pragma once
// Per-vertex colours for looking at the embedding and the damage: the paper's figures colour the car
// by how much each vertex moved (red most, blue none) and by one control point's influence. Part of
// sandbox (drawing only; an engine taking deform does not need them), still in namespace deform.
#include <deform/skin.hpp>

#include <Eigen/Core>
#include <vector>

namespace deform {

/// Colour ramp for t in [0, 1] (clamped): blue (none) -> cyan -> green -> yellow -> red (most). RGB in [0,
/// 1].
Eigen::Vector3f heatColour(float t);

/// Colour of every vertex by the weight control point `control_index` has on it (0 blue .. 1 red).
std::vector<Eigen::Vector3f> influenceColours(const Skin& skin, uint32_t control_index);

/// Colour of every vertex by |deformed - rest| divided by `full_scale_m` (red at or beyond full scale);
/// full_scale_m <= 0 means the largest displacement present.
std::vector<Eigen::Vector3f> displacementColours(const std::vector<Eigen::Vector3f>& rest_m,
                                                 const std::vector<Eigen::Vector3f>& deformed_m,
                                                 float full_scale_m = 0.0f);

}  // namespace deform
