#pragma once
// A car's render mesh following its control points through the skin (deform/skin.hpp, idw or mls):
// weights built once from the rest control points, then per frame only the vertices that a moved
// control point influences are recomputed (deform::Skin::deformMoved, DESIGN.md section 8), and only
// the normals of the vertices next to them (deform::VertexNormals).
#include <vehicle/simulation.hpp>

#include <deform/mesh.hpp>
#include <deform/skin.hpp>
#include <deform/vertex_normals.hpp>

#include <cstdint>
#include <vector>

namespace scenes {

class CarSkin {
 public:
  /// Skin of `body` (vehicle frame) in `control_rest_m` with the car's alpha, k_nearest and skin_method.
  CarSkin(const deform::Mesh& body, const std::vector<Eigen::Vector3d>& control_rest_m,
          const vehicle::DeformationSettings& settings);

  /// Moves the vertices for control-point displacements c_i - c_i0 [m]; recomputes only the vertices of
  /// points whose displacement changed since the last update, and the normals of the vertices sharing a
  /// triangle with one of those (bit-identical to a full deform and deform::computeVertexNormals; the
  /// first update that moves anything recomputes every normal, replacing those the body came with).
  /// Returns the vertices recomputed.
  std::size_t update(const std::vector<Eigen::Vector3d>& displacements_m);

  /// The deformed mesh now (vehicle frame), normals up to date.
  const deform::Mesh& mesh() const { return mesh_; }
  const std::vector<Eigen::Vector3f>& restPositions() const { return rest_m_; }
  const deform::Skin& skin() const { return skin_; }

 private:
  deform::Skin skin_;
  std::vector<Eigen::Vector3f> rest_m_;
  deform::Mesh mesh_;
  std::vector<Eigen::Vector3d> last_displacements_m_;
  std::vector<uint8_t> moved_;
  deform::VertexNormals normals_;           ///< cached triangle normals, for partial normal updates
  bool normals_computed_ = false;           ///< every normal computed from the triangles at least once
  std::vector<uint8_t> vertex_recomputed_;  ///< scratch: vertices the last update moved
};

}  // namespace scenes
