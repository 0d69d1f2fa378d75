#pragma once
// The crash test's crush profile (vehicle::crushProfile) measured on the car's own surface: the render
// mesh as its skin moves it, against the render mesh at rest. The control surface's own profile
// (vehicle::CrashMetrics::residual_crush_m) compares shapes that change with the level of detail: a
// 60-point hull cuts the sedan's front corners 12 cm behind the car. The render mesh at rest is the same
// at every level, so only the crush can differ (docs/CRASH_CALIBRATION.md, "Convergence").
#include <vehicle/simulation.hpp>

#include <deform/mesh.hpp>

#include <Eigen/Core>
#include <vector>

namespace scenes {

/// vehicle::crushStations of `body` at rest against its vertices `now_m` (vehicle frame), looking along
/// `direction` (horizontal, out of the struck end): the height is the rest mesh's most protruding
/// vertex's, the stations span its width. Throws deform::InputError when `now_m` is not one position per
/// vertex.
vehicle::CrushStations surfaceCrush(const deform::Mesh& body, const std::vector<Eigen::Vector3f>& now_m,
                                    const Eigen::Vector3d& direction);

}  // namespace scenes
