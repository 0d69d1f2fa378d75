#pragma once
// Baseline: Bullet's soft body (btSoftBody, Debian's libbullet, double precision) on the same meshes,
// for `bench grid`: its cost per frame, and whether it survives the wall crash. Settings are those of
// Bullet's own soft-body demos for a closed shell that must keep its shape: linear stiffness 0.9,
// volume conservation (kVC 20) and pose matching (kMT 0.05), 4 position iterations, the default
// soft-rigid collision (signed distance fields, SDF_RS).
#include <deform/mesh.hpp>

#include <cstddef>
#include <string>

namespace sandbox::baselines {

struct SoftBodyCost {
  std::size_t nodes = 0, links = 0, faces = 0;
  double build_ms = 0;
  double ms_per_frame = 0;  ///< median over the frames
  bool finite = true;       ///< every node finite at the end
};

/// A soft body of `mesh` (one node per vertex, one link per edge, its triangles as faces) resting just
/// above a ground plane, stepped `frames` 60 Hz frames of `substeps` fixed internal steps each.
SoftBodyCost bulletSoftBodyCost(const deform::Mesh& mesh, double mass_kg, int frames, int substeps);

struct SoftBodyCrash {
  double speed_kmh = 0;
  bool finite = true;
  bool tunnelled = false;         ///< a node reached the wall's far face
  double max_extent_growth = 0;   ///< largest bounding-box diagonal over the rest one, minus 1 [-]
  double max_node_speed_mps = 0;  ///< fastest node at any step [m/s]
  double residual_dent_m = 0;     ///< largest node displacement at the end, centroid motion removed [m]
  bool stable = false;            ///< finite, not tunnelled, extent below 2x, speeds below 10x the impact
  std::string verdict;            ///< one line
};

/// wall_crash for the soft body: launched along +X at speed_kmh into a rigid 0.2 m wall (4 m wide, 2 m
/// high) whose near face is 1 m ahead of the body's front, on the ground, for duration_s at physics_hz.
SoftBodyCrash bulletWallCrash(const deform::Mesh& mesh, double mass_kg, double speed_kmh, double duration_s,
                              double physics_hz);

}  // namespace sandbox::baselines
