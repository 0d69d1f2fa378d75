#pragma once
// A car's render mesh following its control points through the skin (Kenwright 2015, equation 1):
// weights built once from the rest control points, then per frame only the vertices that a moved
// control point influences are recomputed (deform::Skin::deformMoved, DESIGN.md section 8).
#include <vehicle/simulation.hpp>

#include <deform/mesh.hpp>
#include <deform/skin.hpp>

#include <cstdint>
#include <vector>

namespace scenes {

class CarSkin {
 public:
  /// Skin of `body` (vehicle frame) in `control_rest_m` with the car's alpha and k_nearest.
  CarSkin(const deform::Mesh& body, const std::vector<Eigen::Vector3d>& control_rest_m,
          const vehicle::DeformationSettings& settings);

  /// Moves the vertices for control-point displacements c_i - c_i0 [m]; recomputes only the vertices of
  /// points whose displacement changed since the last update, and the normals when any did. Returns the
  /// vertices recomputed.
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
};

}  // namespace scenes
