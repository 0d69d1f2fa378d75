// loadVehicleModel: any file assimp reads, or a "builtin:" spec, into the vehicle frame (metres, X forward,
// Y left, Z up). Format defaults and what assimp 5.2.5 does on its own are in mesh_import.hpp.
#include <deform/error.hpp>
#include <deform/mesh_import.hpp>

#include "contained_read.hpp"

#include <assimp/commonMetaData.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <Eigen/Geometry>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace deform {
namespace {

std::string trimmed(const std::string& text) {
  const auto not_space = [](unsigned char c) { return !std::isspace(c); };
  auto begin = std::find_if(text.begin(), text.end(), not_space);
  auto end = std::find_if(text.rbegin(), text.rend(), not_space).base();
  if (begin >= end) return {};
  std::string out(begin, end);
  while (!out.empty() && (out.back() == '.' || std::isspace(static_cast<unsigned char>(out.back()))))
    out.pop_back();
  return out;
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string formatName(const std::string& ext) {
  if (ext == "gltf" || ext == "glb") return "glTF";
  std::string upper = ext;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return upper.empty() ? "unknown" : upper;
}

std::string numberText(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// The <up_axis> of a COLLADA file's top-level <asset> (COLLADA's default Y_UP when it has none).
Axis colladaUpAxis(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const std::size_t asset_end = head.find("</asset>");
  const std::size_t tag = head.find("<up_axis>");
  if (tag == std::string::npos || (asset_end != std::string::npos && tag > asset_end)) return Axis::PosY;
  const std::size_t start = tag + 9;
  const std::size_t stop = head.find('<', start);
  const std::string value = trimmed(head.substr(start, stop == std::string::npos ? 0 : stop - start));
  if (value == "Z_UP") return Axis::PosZ;
  if (value == "X_UP") return Axis::PosX;
  return Axis::PosY;
}

/// Refuses, before assimp sees it, a PLY file (by content, whatever its extension: assimp also picks the
/// PLY reader by the "ply" signature) whose header has no end_header line within its first MiB: assimp
/// 5.2.4 reads such a file forever (found by fuzz_mesh_ply, tests/fuzz/regressions/mesh_ply/;
/// docs/STABILITY.md).
void checkPlyHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 20, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  // assimp takes a file for PLY by its first three bytes alone ("ply>333...", found by fuzz_mesh_ply, had
  // it reading forever as well).
  const bool ply = head.size() >= 3 && head.compare(0, 3, "ply") == 0;
  if (!ply) return;
  for (std::size_t line = 0; line < head.size();) {
    const std::size_t end = head.find('\n', line);
    if (trimmed(head.substr(line, end == std::string::npos ? std::string::npos : end - line)) == "end_header")
      return;
    if (end == std::string::npos) break;
    line = end + 1;
  }
  throw InputError(path + ": cannot read as a mesh (a PLY header without an end_header line)");
}

/// An FBX axis from its index (0 X, 1 Y, 2 Z) and sign.
std::optional<Axis> fbxAxis(int index, int sign) {
  switch (index) {
    case 0:
      return sign < 0 ? Axis::NegX : Axis::PosX;
    case 1:
      return sign < 0 ? Axis::NegY : Axis::PosY;
    case 2:
      return sign < 0 ? Axis::NegZ : Axis::PosZ;
    default:
      return std::nullopt;
  }
}

/// The file's own conventions: default axes and the metres per file unit the importer must apply.
struct FileConventions {
  Axis up = Axis::PosZ;
  Axis forward = Axis::PosX;
  double unit_m = 1.0;
};

FileConventions fileConventions(const std::string& ext, const std::string& path, const aiScene& scene) {
  FileConventions c;
  if (ext == "gltf" || ext == "glb") {
    c.up = Axis::PosY;
    c.forward = Axis::PosZ;
  } else if (ext == "dae") {
    // VCGLib (MeshLab) writes <up_axis>Y_UP</up_axis> whatever the data is (a fixed default in its
    // exporter): such a declaration says nothing, so the file is taken as Z up like an OBJ or STL.
    aiString generator;
    const bool placeholder_up = scene.mMetaData != nullptr &&
                                scene.mMetaData->Get(AI_METADATA_SOURCE_GENERATOR, generator) &&
                                std::string(generator.C_Str()).find("VCGLib") != std::string::npos;
    c.up = placeholder_up ? Axis::PosZ : colladaUpAxis(path);
    c.forward = c.up == Axis::PosZ ? Axis::PosX : Axis::PosZ;
  } else if (ext == "fbx") {
    int up_index = 1, up_sign = 1, front_index = 2, front_sign = 1;
    float unit_cm = 1.0f;
    double unit_cm_double = 1.0;
    if (scene.mMetaData != nullptr) {
      scene.mMetaData->Get("UpAxis", up_index);
      scene.mMetaData->Get("UpAxisSign", up_sign);
      scene.mMetaData->Get("FrontAxis", front_index);
      scene.mMetaData->Get("FrontAxisSign", front_sign);
      if (scene.mMetaData->Get("UnitScaleFactor", unit_cm))
        unit_cm_double = unit_cm;
      else
        scene.mMetaData->Get("UnitScaleFactor", unit_cm_double);
    }
    const std::optional<Axis> up = fbxAxis(up_index, up_sign);
    const std::optional<Axis> front = fbxAxis(front_index, front_sign);
    c.up = Axis::PosY;
    c.forward = Axis::PosZ;
    if (up && front && up_index != front_index) {
      c.up = *up;
      c.forward = *front;
    }
    // UnitScaleFactor is centimetres per file unit; FBX's own default is 1 (centimetres).
    c.unit_m = (std::isfinite(unit_cm_double) && unit_cm_double > 0 ? unit_cm_double : 1.0) * 0.01;
  }
  return c;
}

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  for (unsigned r = 0; r < 4; ++r)
    for (unsigned c = 0; c < 4; ++c) out(r, c) = static_cast<double>(m[r][c]);
  return out;
}

/// Walks the node tree and appends every referenced mesh, once per instance, already in the vehicle frame.
class SceneCollector {
 public:
  SceneCollector(const aiScene& scene, const std::string& source, const Eigen::Matrix4d& to_vehicle,
                 ImportReport& report, Mesh& mesh)
      : scene_(scene), source_(source), to_vehicle_(to_vehicle), report_(report), mesh_(mesh) {}

  void visit(const aiNode& node, const Eigen::Matrix4d& parent, bool use_own_transform) {
    const Eigen::Matrix4d global =
        use_own_transform ? Eigen::Matrix4d(parent * toEigen(node.mTransformation)) : parent;
    if (!global.allFinite())
      throw InputError(source_ + ": node '" + node.mName.C_Str() + "' has a non-finite transform");
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      if (node.mMeshes[i] >= scene_.mNumMeshes) continue;
      addInstance(*scene_.mMeshes[node.mMeshes[i]], global);
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) visit(*node.mChildren[c], global, true);
  }

  std::size_t meshesWithoutTriangles() const { return meshes_without_triangles_; }

 private:
  void addInstance(const aiMesh& part, const Eigen::Matrix4d& node_to_file) {
    const Eigen::Matrix3d linear = node_to_file.topLeftCorner<3, 3>();
    const double det = linear.determinant();
    const double column_scale = linear.col(0).norm() * linear.col(1).norm() * linear.col(2).norm();
    if (!(std::abs(det) > 1e-9 * column_scale)) {  // a scale of 0 on some axis: a hidden or flattened node
      ++report_.skipped_instances;
      return;
    }
    const bool mirrored = det < 0;  // a mirroring node turns the winding inside out: reverse it back
    const Eigen::Matrix4d to_vehicle = to_vehicle_ * node_to_file;

    std::vector<std::int64_t> local_to_mesh(part.mNumVertices, -1);
    std::size_t triangles = 0;
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no surface
      Triangle t{};
      for (unsigned k = 0; k < 3; ++k) {
        const unsigned v = face.mIndices[k];
        if (v >= part.mNumVertices)
          throw InputError(source_ + ": mesh '" + part.mName.C_Str() + "' face " + std::to_string(f) +
                           " uses vertex " + std::to_string(v) + " of " + std::to_string(part.mNumVertices));
        if (local_to_mesh[v] < 0) {
          const aiVector3D& p = part.mVertices[v];
          const Eigen::Vector3d file_p(static_cast<double>(p.x), static_cast<double>(p.y),
                                       static_cast<double>(p.z));
          if (!file_p.allFinite())
            throw InputError(source_ + ": mesh '" + part.mName.C_Str() + "' vertex " + std::to_string(v) +
                             " has a non-finite coordinate (NaN or infinity)");
          const Eigen::Vector3d q = (to_vehicle * file_p.homogeneous()).head<3>();
          local_to_mesh[v] = static_cast<std::int64_t>(mesh_.positions_m.size());
          mesh_.positions_m.push_back(q.cast<float>());
        }
        t[k] = static_cast<std::uint32_t>(local_to_mesh[v]);
      }
      if (mirrored) std::swap(t[1], t[2]);
      mesh_.triangles.push_back(t);
      ++triangles;
    }
    if (triangles == 0) {
      ++meshes_without_triangles_;
      return;
    }
    ++report_.mesh_instances;
  }

  const aiScene& scene_;
  const std::string& source_;
  Eigen::Matrix4d to_vehicle_;
  ImportReport& report_;
  Mesh& mesh_;
  std::size_t meshes_without_triangles_ = 0;
};

void checkScale(double scale, const std::string& source) {
  if (!std::isfinite(scale) || scale <= 0)
    throw InputError(source + ": scale must be a finite number above zero (got " + numberText(scale) + ")");
}

VehicleModel loadBuiltin(const std::string& spec, const ImportOptions& options, ImportReport& report) {
  checkScale(options.scale, spec);
  report.format = "builtin";
  report.up = options.up.value_or(Axis::PosZ);
  report.forward = options.forward.value_or(Axis::PosX);
  const Eigen::Matrix3d rotation = vehicleFrameRotation(report.up, report.forward, spec);
  VehicleModel model = makeBuiltin(spec);
  model.source = spec;
  report.raw_vertices = model.body.positions_m.size();
  report.mesh_instances = 1;
  if (options.scale == 1.0 && rotation.isIdentity()) return model;
  const Eigen::Matrix3f r = rotation.cast<float>();
  const auto s = static_cast<float>(options.scale);
  for (auto& p : model.body.positions_m) p = s * (r * p);
  for (auto& n : model.body.normals) n = r * n;
  for (auto& wheel : model.wheels) {
    wheel.centre_m = options.scale * (rotation * wheel.centre_m);
    wheel.radius_m *= options.scale;
    wheel.width_m *= options.scale;
  }
  checkMesh(model.body, spec);
  return model;
}

/// assimp's part of loadFile (run in a child process): the file's meshes, placed and in the vehicle frame,
/// before welding; fills the report's axes, unit and instance counts.
Mesh readWithAssimp(const std::string& path, const std::string& ext, const ImportOptions& options,
                    ImportReport& report) {
  Assimp::Importer importer;
  // Keep a DAE file's own axes (assimp would rotate Z_UP to Y_UP through the root node); its <unit> stays.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    const std::string why = trimmed(importer.GetErrorString());
    if (why.find("contains no faces") != std::string::npos)  // a point cloud: assimp's validation refuses it
      throw InputError(path + ": no triangles (" + why + ")");
    throw InputError(path + ": cannot read as a mesh (" + (why.empty() ? "unknown format" : why) + ")");
  }
  if (scene->mRootNode == nullptr) throw InputError(path + ": no triangles (the file has no scene nodes)");

  const FileConventions conventions = fileConventions(ext, path, *scene);
  report.up = options.up.value_or(conventions.up);
  report.forward = options.forward.value_or(conventions.forward);
  report.file_unit_m = conventions.unit_m;
  const Eigen::Matrix3d rotation = vehicleFrameRotation(report.up, report.forward, path);

  Eigen::Matrix4d to_vehicle = Eigen::Matrix4d::Identity();
  to_vehicle.topLeftCorner<3, 3>() = (options.scale * conventions.unit_m) * rotation;

  Mesh mesh;
  SceneCollector collector(*scene, path, to_vehicle, report, mesh);
  collector.visit(*scene->mRootNode, Eigen::Matrix4d::Identity(), options.root_transform);

  if (mesh.triangles.empty()) {
    std::string why = "the file has no meshes";
    if (collector.meshesWithoutTriangles() > 0)
      why = std::to_string(collector.meshesWithoutTriangles()) + " mesh(es) with only points or lines";
    else if (report.skipped_instances > 0)
      why = "every mesh sits under a node scaled to zero";
    throw InputError(path + ": no triangles (" + why + ")");
  }
  return mesh;
}

VehicleModel loadFile(const std::string& path, const ImportOptions& options, ImportReport& report) {
  checkScale(options.scale, path);
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw InputError(path + ": file not found");
  if (std::filesystem::is_directory(status)) throw InputError(path + ": is a directory, not a mesh file");

  const std::string ext = lowerExtension(path);
  report.format = formatName(ext);

  checkPlyHeader(path);
  // assimp aborts on some malformed files (an assertion inside its triangulation, found by fuzz_mesh_ply):
  // it reads in a child process, and such a file is refused instead of ending the program.
  VehicleModel model;
  model.source = path;
  model.body = readContained(
      path, [&](ImportReport& child_report) { return readWithAssimp(path, ext, options, child_report); },
      report, options.importer_cpu_limit_s);
  Mesh& mesh = model.body;
  checkMesh(mesh, path);  // non-finite after scaling, zero extent

  report.raw_vertices = mesh.positions_m.size();
  const WeldResult weld = weldPositions(mesh);
  report.merged_vertices = weld.merged_vertices;
  report.degenerate_triangles = weld.degenerate_triangles;
  report.unused_vertices = weld.unused_vertices;
  if (mesh.triangles.empty())
    throw InputError(path + ": no triangles (every triangle has zero area after welding)");
  computeVertexNormals(mesh);
  return model;
}

}  // namespace

VehicleModel loadVehicleModel(const std::string& spec, const ImportOptions& options, ImportReport& report) {
  report = ImportReport{};
  if (isBuiltinSpec(spec)) return loadBuiltin(spec, options, report);
  return loadFile(spec, options, report);
}

VehicleModel loadVehicleModel(const std::string& spec, const ImportOptions& options) {
  ImportReport report;
  return loadVehicleModel(spec, options, report);
}

}  // namespace deform
