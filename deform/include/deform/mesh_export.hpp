#pragma once
// Writing a mesh for any 3D tool through assimp's exporter (deform_io): binary glTF (.glb) or Wavefront OBJ
// (.obj).
#include <deform/mesh.hpp>

#include <string>

namespace deform {

/// Writes `mesh` (vehicle frame: X forward, Y left, Z up, metres) to `path`; the format follows the
/// extension. GLB is written Y up with the car's front along +Z (glTF 2.0's convention), OBJ as it is
/// (Z up, X forward: what the importer assumes for OBJ). Throws InputError naming the path for
/// another extension, std::runtime_error with assimp's message when writing fails.
void exportMesh(const deform::Mesh& mesh, const std::string& path);

/// Writes `mesh` as it is (no change of axes) in assimp's export format `format_id` ("obj", "stl", "stlb",
/// "ply", "plyb", "glb2", ...; Assimp::Exporter lists them) to `path`, whatever its extension. Throws
/// std::runtime_error with assimp's message when writing fails.
void exportMeshAs(const deform::Mesh& mesh, const std::string& format_id, const std::string& path);

}  // namespace deform
