#include <deform/mesh_export.hpp>

#include <deform/error.hpp>

#include <assimp/scene.h>
#include <assimp/Exporter.hpp>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace deform {

namespace {

/// `mesh` as a one-mesh assimp scene written in assimp's format `format_id`; `gltf_axes`: turned from the
/// vehicle frame into glTF's (Y up, front along +Z).
void writeScene(const Mesh& mesh, const std::string& format_id, const std::string& path, bool gltf_axes) {
  // A glTF asset is Y up with its front along +Z, so +X is the car's left: (x, y, z)_glTF = (y, z, x).
  const auto convert = [gltf_axes](const Eigen::Vector3f& v) {
    return gltf_axes ? aiVector3D(v.y(), v.z(), v.x()) : aiVector3D(v.x(), v.y(), v.z());
  };
  aiScene scene;  // owns everything below and frees it
  scene.mRootNode = new aiNode();
  scene.mRootNode->mName = "vehicle";
  scene.mMaterials = new aiMaterial* [1] { new aiMaterial() };
  scene.mNumMaterials = 1;
  auto* out = new aiMesh();
  scene.mMeshes = new aiMesh* [1] { out };
  scene.mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned int[1]{0};
  scene.mRootNode->mNumMeshes = 1;
  out->mName = "body";
  out->mMaterialIndex = 0;
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  out->mNumVertices = static_cast<unsigned int>(mesh.positions_m.size());
  out->mVertices = new aiVector3D[out->mNumVertices];
  for (unsigned int i = 0; i < out->mNumVertices; ++i) out->mVertices[i] = convert(mesh.positions_m[i]);
  if (mesh.normals.size() == mesh.positions_m.size()) {
    out->mNormals = new aiVector3D[out->mNumVertices];
    for (unsigned int i = 0; i < out->mNumVertices; ++i) out->mNormals[i] = convert(mesh.normals[i]);
  }
  out->mNumFaces = static_cast<unsigned int>(mesh.triangles.size());
  out->mFaces = new aiFace[out->mNumFaces];
  for (unsigned int f = 0; f < out->mNumFaces; ++f) {
    aiFace& face = out->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned int[3];
    for (unsigned int k = 0; k < 3; ++k) face.mIndices[k] = mesh.triangles[f][k];
  }
  Assimp::Exporter exporter;
  if (exporter.Export(&scene, format_id, path) != AI_SUCCESS) {
    throw std::runtime_error(path + ": cannot write (" + exporter.GetErrorString() + ")");
  }
}

}  // namespace

void exportMesh(const deform::Mesh& mesh, const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool glb = extension == ".glb";
  if (!glb && extension != ".obj") {
    throw InputError("--out: " + path + ": unknown format (give a .glb or .obj file)");
  }
  writeScene(mesh, glb ? "glb2" : "obj", path, glb);
}

void exportMeshAs(const deform::Mesh& mesh, const std::string& format_id, const std::string& path) {
  writeScene(mesh, format_id, path, false);
}

}  // namespace deform
