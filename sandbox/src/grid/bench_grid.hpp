#pragma once
// Render-mesh vertices against control points (DESIGN.md section 6): the built-in sedan at several
// resolutions against several levels of detail, what each costs to build, to hold and per frame, beside
// the baselines a user could pick instead (every render vertex simulated; Bullet's soft body).
#include "baselines/bullet_soft_body.hpp"

#include <deform/control_mesh.hpp>
#include <deform/mesh.hpp>

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace sandbox {

struct GridRow {
  /// "skin K=8", "skin dense", "full-resolution XPBD", "Bullet soft body (control mesh)",
  /// "Bullet soft body (render mesh)".
  std::string method;
  std::size_t vertices = 0;        ///< render-mesh vertices
  std::size_t control_points = 0;  ///< simulated points (the render vertices for the full-resolution ones)
  std::size_t constraints = 0;     ///< of the simulated body (links for Bullet)
  double hull_ms = 0;              ///< convex hull of the render mesh (qhull), once per resolution
  double lod_ms = 0;               ///< hull to N control points
  double body_ms = 0;              ///< masses and constraint arrays (or the baseline's body)
  double skin_ms = 0;              ///< embedding weights
  std::size_t skin_bytes = 0;      ///< embedding weights and indices held
  double step_ms = 0;              ///< one deformation step per 60 Hz frame (4 substeps x 2 iterations)
  double embed_ms = 0;             ///< render mesh following the control points, all vertices, all cores
  double frame_ms() const { return step_ms + embed_ms; }
  std::string note;  ///< e.g. why a cell was skipped
};

struct GridOptions {
  std::vector<std::size_t> vertices = {10000, 100000, 900000, 4000000};
  std::vector<std::size_t> control_points = {8, 30, 60, 250, 1000, 4000};
  /// Dense weights are measured where they take at most this much memory [bytes].
  std::size_t dense_budget_bytes = std::size_t{1500} << 20;
  /// Baselines simulate the render mesh up to this many vertices (the rest would take minutes a step).
  std::size_t full_resolution_max_vertices = 4000000;
  std::size_t bullet_max_vertices = 100000;
  unsigned threads = 0;  ///< for the embedding pass; 0 = all cores
  /// wall_crash speeds at which Bullet's soft body (the 60-point control mesh) is checked [km/h].
  std::vector<double> bullet_crash_speeds_kmh = {56, 250};
  static GridOptions quick();
};

/// A control mesh as a render-style mesh (float positions, its triangles).
deform::Mesh asMesh(const deform::ControlMesh& control);

/// Bullet's soft body of the sedan's 60-point control mesh in wall_crash (500 Hz, 1.2 s) at each of
/// options.bullet_crash_speeds_kmh.
std::vector<baselines::SoftBodyCrash> bulletCrashes(const GridOptions& options);

/// Bullet's soft body crash of bulletCrashes at one speed [km/h].
baselines::SoftBodyCrash bulletCrash(double speed_kmh);

/// The rows of one render-mesh resolution, in runBenchGrid's order (Bullet on the control mesh only when
/// `first_resolution`). `step_ms_of` caches the step's cost per control-point count across resolutions.
std::vector<GridRow> runBenchGridResolution(const GridOptions& options, std::size_t vertices,
                                            bool first_resolution, std::map<std::size_t, double>& step_ms_of,
                                            const std::function<void(const GridRow&)>& on_row = {});

/// Measures every cell; `on_row` is called as each row is done (progress).
std::vector<GridRow> runBenchGrid(const GridOptions& options,
                                  const std::function<void(const GridRow&)>& on_row = {});

}  // namespace sandbox
