// Writes the seed corpora of the fuzz targets into DIR/<target>/ (tools/fuzz.sh adds the shipped scenes and
// the small shared meshes): for each mesh format a small box (the built-in one, 4.2 x 1.8 x 1.4 m, as the
// importer tests use) written by assimp's own exporter, a binary and a text variant where the format has
// both, and a glTF tetrahedron with its buffer inline; for the scene target the shipped scenes with --set
// overrides after NUL bytes (the input layout fuzz_scene.cpp reads).
#include <deform/builtin_meshes.hpp>
#include <deform/mesh_export.hpp>
#include <scenes/scene_file.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fs = std::filesystem;

namespace {

/// `mesh` written in assimp format `format` (deform::exportMeshAs); a failure ends the program.
void exportAs(const deform::Mesh& mesh, const std::string& format, const fs::path& path) {
  fs::create_directories(path.parent_path());
  try {
    deform::exportMeshAs(mesh, format, path.string());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    std::exit(1);
  }
}

void write(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

// A tetrahedron, positions and indices in one inline (base64) buffer: 4 float3 then 12 uint16.
const char* const kTetrahedronGltf = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [0, 0.5, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
    {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}],
  "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
  "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAACAAEAAAABAAMAAAADAAIAAQACAAMA"}]
})";

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds DIR\n");
    return 2;
  }
  const fs::path dir(argv[1]);
  const deform::Mesh box = deform::makeBox({4.2, 1.8, 1.4}, 100);
  exportAs(box, "obj", dir / "mesh_obj" / "box.obj");
  exportAs(box, "stl", dir / "mesh_stl" / "box_text.stl");
  exportAs(box, "stlb", dir / "mesh_stl" / "box_binary.stl");
  exportAs(box, "ply", dir / "mesh_ply" / "box_text.ply");
  exportAs(box, "plyb", dir / "mesh_ply" / "box_binary.ply");
  exportAs(box, "glb2", dir / "mesh_glb" / "box.glb");
  write(dir / "mesh_gltf" / "tetrahedron.gltf", kTetrahedronGltf);

  const char* const overrides[][2] = {
      {"wall_crash", "vehicle.start.speed_kmh=32"},
      {"wall_crash", "obstacles[0].x=3"},
      {"car_to_car", "vehicles.1.deformation={\"preset\": \"fast\"}"},
      {"pole_side", "vehicle.drive.keys.0.t_s=0.5"},
  };
  for (const std::string& name : scenes::shippedSceneNames()) {
    std::ifstream in(fs::path(scenes::shippedScenesDir()) / (name + ".json"), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    write(dir / "scene" / (name + ".json"), text);
    int n = 0;
    for (const auto& [scene, set] : overrides)
      if (name == scene) write(dir / "scene" / (name + "_set" + std::to_string(n++)), text + '\0' + set);
  }
  std::printf("wrote the seeds into %s\n", dir.string().c_str());
  return 0;
}
