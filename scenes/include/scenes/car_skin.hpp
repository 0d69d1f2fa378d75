#pragma once
// A car's render mesh following its control points through the skin (deform/skin.hpp, idw, mls or spline):
// weights built once from the rest control points, then per frame only the vertices that a moved
// control point influences are recomputed (deform::Skin::deformMoved, DESIGN.md section 8), and only
// the normals of the vertices next to them (deform::VertexNormals). Then the vertices inside what the car
// touches are moved onto its surface (deform/surface_projection.hpp), found through a grid over the rest
// positions; a projected vertex goes back to the skin's position before it is tested again.
#include <vehicle/simulation.hpp>

#include <deform/contact_shapes.hpp>
#include <deform/vertex_grid.hpp>

#include <deform/mesh.hpp>
#include <deform/skin.hpp>
#include <deform/vertex_normals.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

namespace scenes {

class CarSkin {
 public:
  /// What every car of one build shares (the same body mesh, control mesh and skin settings; DESIGN.md
  /// section 8): immutable once made. A car keeps only its deformed positions and normals and a few
  /// flags per vertex (`sandbox bench memory`).
  struct Build {
    std::shared_ptr<const deform::Skin> skin;
    std::vector<Eigen::Vector3f> rest_m;  ///< the body's vertices [m]
    /// The rest normals: the body's own, or (normals_from_triangles) computed once from the triangles.
    std::vector<Eigen::Vector3f> rest_normals;
    bool normals_from_triangles = false;
    std::vector<deform::Triangle> triangles;
    std::shared_ptr<const deform::VertexTriangles> around;  ///< triangles around each vertex
    deform::VertexGrid grid;              ///< rest positions, for the vertices near an obstacle
    Eigen::Vector3d interior_m{0, 0, 0};  ///< middle of the rest bounding box [m]
    double displacement_gain = 1;     ///< largest sum of |weights| of a vertex: |v - v0| <= gain max |d_i|
    bool nonnegative_weights = true;  ///< every weight >= 0 (idw): a vertex moves within its points' hull
    std::size_t bytes() const;        ///< heap bytes held, the weights included
  };
  /// The shared part for `body` with weights built beforehand by buildSkin for it.
  static std::shared_ptr<const Build> share(const deform::Mesh& body,
                                            std::shared_ptr<const deform::Skin> skin);
  /// The weights of `body`'s vertices in `control_rest_m` with the car's alpha, k_nearest and
  /// skin_method.
  static std::shared_ptr<const deform::Skin> buildSkin(const deform::Mesh& body,
                                                       const std::vector<Eigen::Vector3d>& control_rest_m,
                                                       const vehicle::DeformationSettings& settings);

  /// One car of a shared build.
  explicit CarSkin(std::shared_ptr<const Build> build);
  /// A car with a build of its own: `body` (vehicle frame) in `control_rest_m` with the car's alpha,
  /// k_nearest and skin_method.
  CarSkin(const deform::Mesh& body, const std::vector<Eigen::Vector3d>& control_rest_m,
          const vehicle::DeformationSettings& settings);

  /// Moves the vertices for control-point displacements c_i - c_i0 [m]; recomputes only the vertices of
  /// points whose displacement changed since the last update, and the normals of the vertices sharing a
  /// triangle with one of those (bit-identical to a full deform and deform::computeVertexNormals; the
  /// first update that moves anything recomputes every normal, replacing those the body came with).
  /// Returns the vertices recomputed.
  std::size_t update(const std::vector<Eigen::Vector3d>& displacements_m);

  /// As update(displacements_m), then every vertex inside one of `obstacles` (vehicle frame, now) is
  /// projected onto its surface on the side of the car's interior (deform::projectOutOf), the vertices
  /// projected last time having been returned to the skin's position first. Only the vertices near an
  /// obstacle are tested (deform::verticesNear). Returns the vertices whose position changed (0 for a
  /// car resting against an obstacle: put back and projected again to the same place is no change).
  std::size_t update(const std::vector<Eigen::Vector3d>& displacements_m,
                     const std::vector<deform::ContactShape>& obstacles);

  /// What the last update's projection did.
  struct ProjectionStats {
    std::size_t tested = 0;         ///< vertices tested against an obstacle (with repeats across obstacles)
    std::size_t projected = 0;      ///< vertices moved onto an obstacle's surface
    std::size_t tested_ground = 0;  ///< of `tested`, those against a half-space (the ground)
    double ms = 0;                  ///< time of the restore, the queries and the projection [ms]
  };
  const ProjectionStats& lastProjection() const { return last_projection_; }
  /// The most any vertex can be from its rest position for these control-point displacements [m].
  double displacementBound_m(const std::vector<Eigen::Vector3d>& displacements_m) const;
  /// The rest mesh's bounding box (vehicle frame) [m].
  const deform::Aabb& restBounds() const { return build_->grid.bounds(); }
  /// Where the skin puts every vertex now, before the projection (vehicle frame) [m].
  Eigen::Vector3f skinPosition(std::size_t vertex) const;

  /// The deformed vertices now (vehicle frame) [m], their normals (up to date), and the triangles.
  const std::vector<Eigen::Vector3f>& positions() const { return positions_m_; }
  const std::vector<Eigen::Vector3f>& normals() const { return normals_; }
  const std::vector<deform::Triangle>& triangles() const { return build_->triangles; }
  /// The deformed mesh now as a mesh of its own (a copy).
  deform::Mesh deformedMesh() const;
  const std::vector<Eigen::Vector3f>& restPositions() const { return build_->rest_m; }
  const deform::Skin& skin() const { return *build_->skin; }
  const Build& build() const { return *build_; }
  /// Heap bytes this car holds of its own (not the shared build).
  std::size_t ownBytes() const;

 private:
  std::shared_ptr<const Build> build_;
  std::vector<Eigen::Vector3f> positions_m_;
  std::vector<Eigen::Vector3f> normals_;
  std::vector<Eigen::Vector3d> last_displacements_m_;
  std::vector<uint8_t> moved_;
  deform::VertexNormals normal_updates_;    ///< partial normal updates
  bool normals_computed_ = false;           ///< every normal computed from the triangles at least once
  std::vector<uint8_t> vertex_recomputed_;  ///< scratch: vertices the last update moved

  /// How far along the unit `into` any vertex can have moved: the reach of a half-space's test [m].
  double reachAlong_m(const std::vector<Eigen::Vector3d>& displacements_m, const Eigen::Vector3d& into) const;
  std::vector<uint32_t> projected_;  ///< vertices off the skin's position (on an obstacle's surface)
  std::vector<Eigen::Vector3f> projected_from_m_;  ///< their skin positions [m]
  std::vector<uint8_t> is_projected_;              ///< one flag per vertex, for projected_
  /// Projected vertices put back to the skin this update, with where they stood before [m].
  std::vector<std::pair<uint32_t, Eigen::Vector3f>> restored_;
  std::vector<uint32_t> candidates_;  ///< scratch
  ProjectionStats last_projection_;
};

/// The skins (weights alone) of a run's cars: one per body mesh, control mesh and skin settings. Keyed
/// by the addresses of the body and of the control points, which stay put for the run (scenes::SceneRun's
/// models and vehicle::Simulation's control meshes).
class SkinCache {
 public:
  std::shared_ptr<const deform::Skin> get(const deform::Mesh& body,
                                          const std::vector<Eigen::Vector3d>& control_rest_m,
                                          const vehicle::DeformationSettings& settings);

 private:
  using Key = std::tuple<const void*, const void*, double, std::size_t, int>;
  std::map<Key, std::shared_ptr<const deform::Skin>> skins_;
};

/// The shared builds of a run's cars: one per skin of SkinCache (DESIGN.md section 8).
class CarSkinBuilds {
 public:
  std::shared_ptr<const CarSkin::Build> get(const deform::Mesh& body,
                                            const std::vector<Eigen::Vector3d>& control_rest_m,
                                            const vehicle::DeformationSettings& settings);

 private:
  SkinCache skins_;
  std::map<const deform::Skin*, std::shared_ptr<const CarSkin::Build>> builds_;
};

}  // namespace scenes
