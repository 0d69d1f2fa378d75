#pragma once
// The crash test's crush profile (vehicle::crushProfile) measured on the car's own surface: the render
// mesh as its skin moves it, against the render mesh at rest. The control surface's own profile
// (vehicle::CrashMetrics::residual_crush_m) compares shapes that change with the level of detail: a
// 60-point hull cuts the sedan's front corners 12 cm behind the car. The render mesh at rest is the same
// at every level, so only the crush can differ (docs/CRASH_CALIBRATION.md, "Convergence").
#include <vehicle/simulation.hpp>

#include <deform/mesh.hpp>
#include <deform/skin.hpp>

#include <Eigen/Core>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

namespace scenes {

struct SurfaceCrush {
  /// Intrusion at six equally spaced stations across the width of the rest mesh, in order along up x
  /// direction, NaN where a station's line misses the mesh [m].
  std::vector<double> profile_m;
  double height_m = 0;              ///< of the rest mesh's most protruding vertex along the direction [m]
  double residual_crush_m = 0;      ///< the stations' mean (those that hit) [m]
  double max_residual_crush_m = 0;  ///< the largest station [m]
};

/// `body` at rest against its vertices `now_m` (vehicle frame), looking along `direction` (horizontal,
/// out of the struck end). Throws deform::InputError when `now_m` is not one position per vertex.
SurfaceCrush surfaceCrush(const deform::Mesh& body, const std::vector<Eigen::Vector3f>& now_m,
                          const Eigen::Vector3d& direction);

/// The skins that move render meshes for surfaceCrush: only the weights (no normals, no grid), one per
/// body mesh, control mesh and skin settings, so the cars of one build share one. Keyed by the
/// addresses of the body and of the control points, which stay put for a run.
class SurfaceSkins {
 public:
  std::shared_ptr<const deform::Skin> get(const deform::Mesh& body,
                                          const std::vector<Eigen::Vector3d>& control_rest_m,
                                          const vehicle::DeformationSettings& settings);

 private:
  using Key = std::tuple<const void*, const void*, double, std::size_t, int>;
  std::map<Key, std::shared_ptr<const deform::Skin>> skins_;
};

}  // namespace scenes
