#pragma once
// The render mesh: the high-resolution surface that follows the control points.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace deform {

using Triangle = std::array<uint32_t, 3>;  ///< three vertex indices, counter-clockwise from outside

/// A triangle mesh in the vehicle frame (DESIGN.md section 2): metres, X forward, Y left, Z up.
/// Positions are float (render data); physics uses double.
struct Mesh {
  std::vector<Eigen::Vector3f> positions_m;  ///< vertex positions [m]
  std::vector<Triangle> triangles;           ///< counter-clockwise seen from outside
  std::vector<Eigen::Vector3f> normals;      ///< unit vertex normals; empty or one per position
};

/// Axis-aligned bounding box [m].
struct Aabb {
  Eigen::Vector3d min_m{0, 0, 0};  ///< lowest corner [m]
  Eigen::Vector3d max_m{0, 0, 0};  ///< highest corner [m]
  Eigen::Vector3d size_m() const { return max_m - min_m; }
  double diagonal_m() const { return size_m().norm(); }
};

/// The box around every vertex of `mesh` [m].
Aabb boundingBox(const Mesh& mesh);

/// Area-weighted vertex normals from the triangles (replaces mesh.normals). Each vertex sums its
/// triangles in increasing triangle order (VertexNormals, deform/vertex_normals.hpp, gives the same bits).
void computeVertexNormals(Mesh& mesh);

/// Refuses a mesh that cannot be used: no vertices, no triangles, an index out of range, a non-finite
/// coordinate or zero extent. Throws InputError whose message starts with `source`.
void checkMesh(const Mesh& mesh, std::string_view source);

/// Appends `part` to `mesh` (indices offset), e.g. to draw wheels with the body.
void appendMesh(Mesh& mesh, const Mesh& part);

}  // namespace deform
