// loadVehicleModel (deform/io/mesh_import.cpp), weldPositions (weld.cpp) and vehicleFrameRotation
// (vehicle_frame.cpp): axes, units, welding, instancing, bad input, and every shared third-party mesh.
#include <deform/error.hpp>
#include <deform/mesh_import.hpp>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "support.hpp"

namespace fs = std::filesystem;
using deform::Axis;
using deform::ImportOptions;
using deform::ImportReport;
using deform::InputError;

namespace {

const Axis kAxes[] = {Axis::PosX, Axis::NegX, Axis::PosY, Axis::NegY, Axis::PosZ, Axis::NegZ};

/// A scratch folder for this test run's files, removed at the end.
struct TempDir {
  fs::path path;
  TempDir() {
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path = fs::temp_directory_path() / ("deform_import_test_" + std::to_string(stamp));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path file = path / name;
    std::ofstream(file, std::ios::binary) << text;
    return file.string();
  }
};

/// An axis-aligned box from (0,0,0) to `size`, each face with its own four vertices (24 in all, as a
/// flat-shaded export has them), faces counter-clockwise from outside.
std::string boxObj(double sx, double sy, double sz) {
  std::string text;
  const auto v = [&](double x, double y, double z) {
    text +=
        "v " + std::to_string(x * sx) + " " + std::to_string(y * sy) + " " + std::to_string(z * sz) + "\n";
  };
  // -x, +x, -y, +y, -z, +z faces
  v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0);
  v(1, 0, 0), v(1, 1, 0), v(1, 1, 1), v(1, 0, 1);
  v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1);
  v(0, 1, 0), v(0, 1, 1), v(1, 1, 1), v(1, 1, 0);
  v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0);
  v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1);
  for (int f = 0; f < 6; ++f) {
    const int b = 4 * f + 1;
    text += "f " + std::to_string(b) + " " + std::to_string(b + 1) + " " + std::to_string(b + 2) + " " +
            std::to_string(b + 3) + "\n";
  }
  return text;
}

/// Signed volume of a closed mesh (positive when its triangles wind counter-clockwise from outside).
double signedVolume(const deform::Mesh& mesh) {
  double six_v = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions_m[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.positions_m[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.positions_m[t[2]].cast<double>();
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6;
}

/// The InputError message of `load`, or "" when it does not throw one.
template <class Load>
std::string errorOf(Load load) {
  try {
    load();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

TEST_CASE("vehicleFrameRotation is a proper rotation taking forward to +X and up to +Z", "[import]") {
  int perpendicular_pairs = 0;
  for (Axis up : kAxes) {
    for (Axis forward : kAxes) {
      const Eigen::Vector3d u = deform::axisVector(up);
      const Eigen::Vector3d f = deform::axisVector(forward);
      if (std::abs(u.dot(f)) > 0.5) {
        const std::string message = errorOf([&] { deform::vehicleFrameRotation(up, forward, "car.obj"); });
        CHECK(startsWith(message, "car.obj: "));
        CHECK(message.find("perpendicular") != std::string::npos);
        continue;
      }
      ++perpendicular_pairs;
      const Eigen::Matrix3d r = deform::vehicleFrameRotation(up, forward, "car.obj");
      CHECK(r.determinant() == Approx(1.0));
      CHECK((r * r.transpose()).isIdentity(1e-12));
      CHECK((r * f).isApprox(Eigen::Vector3d::UnitX()));
      CHECK((r * u).isApprox(Eigen::Vector3d::UnitZ()));
    }
  }
  CHECK(perpendicular_pairs == 24);  // every proper axis-aligned rotation exactly once
  CHECK(deform::vehicleFrameRotation(Axis::PosZ, Axis::PosX, "x").isIdentity());
}

TEST_CASE("weldPositions merges identical positions and drops triangles it makes degenerate", "[import]") {
  deform::Mesh mesh;
  // Two triangles of a unit square, each with its own copies of the shared diagonal (-0 on one copy),
  // plus a sliver whose corners 0 and 6 coincide and whose third corner 7 no other triangle uses.
  mesh.positions_m = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-0.0f, 0, 0},
                      {1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {5, 5, 5}};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 6, 7}};
  mesh.normals.assign(mesh.positions_m.size(), Eigen::Vector3f::UnitZ());
  const deform::WeldResult result = deform::weldPositions(mesh);
  CHECK(result.merged_vertices == 3);
  CHECK(result.degenerate_triangles == 1);
  CHECK(result.unused_vertices == 1);
  REQUIRE(mesh.positions_m.size() == 4);
  REQUIRE(mesh.triangles.size() == 2);
  CHECK(mesh.normals.empty());
  // Both triangles now share the diagonal's two vertices.
  CHECK(mesh.triangles[0][0] == mesh.triangles[1][0]);
  CHECK(mesh.triangles[0][2] == mesh.triangles[1][1]);
}

TEST_CASE("loadVehicleModel welds a flat-shaded OBJ box and applies scale and axes", "[import]") {
  TempDir dir;
  const std::string path = dir.write("box.obj", boxObj(4, 2, 1));

  SECTION("defaults for OBJ: Z up, X forward, metres") {
    ImportReport report;
    const deform::VehicleModel model = deform::loadVehicleModel(path, {}, report);
    CHECK(model.source == path);
    CHECK(model.wheels.empty());
    CHECK(report.format == "OBJ");
    CHECK(report.raw_vertices == 24);
    CHECK(report.merged_vertices == 16);
    CHECK(model.body.positions_m.size() == 8);
    CHECK(model.body.triangles.size() == 12);
    REQUIRE(model.body.normals.size() == 8);
    const deform::Aabb box = deform::boundingBox(model.body);
    CHECK(box.size_m().isApprox(Eigen::Vector3d(4, 2, 1), 1e-6));
    CHECK(signedVolume(model.body) == Approx(8.0));  // still wound outward
    // A corner's normal points out of the box, along the diagonal away from its centre.
    for (std::size_t i = 0; i < model.body.positions_m.size(); ++i) {
      const Eigen::Vector3d out = model.body.positions_m[i].cast<double>() - Eigen::Vector3d(2, 1, 0.5);
      CHECK(model.body.normals[i].cast<double>().dot(out) > 0);
    }
  }
  SECTION("scale and a Y-up, -X-forward file") {
    ImportOptions options;
    options.scale = 0.5;
    options.up = Axis::PosY;
    options.forward = Axis::NegX;
    const deform::VehicleModel model = deform::loadVehicleModel(path, options);
    const deform::Aabb box = deform::boundingBox(model.body);
    // File x (length 4, running 0..4) is backwards: vehicle X from -2 to 0. File y is up (2 -> 1 m).
    CHECK(box.min_m.x() == Approx(-2.0));
    CHECK(box.max_m.x() == Approx(0.0).margin(1e-7));
    CHECK(box.size_m().isApprox(Eigen::Vector3d(2, 0.5, 1), 1e-6));
    CHECK(signedVolume(model.body) == Approx(1.0));  // a rotation, not a mirror: still outward
  }
}

TEST_CASE("loadVehicleModel expands instances, skips zero-scale nodes and unmirrors mirrored ones",
          "[import]") {
  // One triangle (0,0,0) (1,0,0) (0,1,0), counter-clockwise seen from glTF +Z, placed by four nodes:
  // plain, moved along +X, flattened (scale 0 on Y: skipped), mirrored in X.
  const std::string gltf = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 2, 3]}],
  "nodes": [
    {"mesh": 0},
    {"mesh": 0, "translation": [5, 0, 0]},
    {"mesh": 0, "scale": [1, 0, 1]},
    {"mesh": 0, "translation": [10, 0, 0], "scale": [-1, 1, 1]}
  ],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36,
               "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]
})";
  TempDir dir;
  const std::string path = dir.write("instances.gltf", gltf);
  ImportReport report;
  const deform::VehicleModel model = deform::loadVehicleModel(path, {}, report);
  CHECK(report.format == "glTF");
  CHECK(report.mesh_instances == 3);
  CHECK(report.skipped_instances == 1);
  CHECK(model.body.triangles.size() == 3);
  CHECK(model.body.positions_m.size() == 9);
  // glTF defaults: up +Y, forward +Z, so file +Z (the triangle's front) is vehicle +X, and file +X is
  // vehicle +Y (left = up x forward: a glTF asset's left is +X).
  REQUIRE(model.body.normals.size() == 9);
  for (const auto& n : model.body.normals) CHECK(n.cast<double>().isApprox(Eigen::Vector3d::UnitX(), 1e-6));
  const deform::Aabb box = deform::boundingBox(model.body);
  CHECK(box.min_m.y() == Approx(0.0).margin(1e-7));
  CHECK(box.max_m.y() == Approx(10.0));
  CHECK(box.size_m().z() == Approx(1.0));
}

/// A tetrahedron 100 x 200 x 300 centimetres along the file's x, y, z, in COLLADA with the given up axis.
std::string tetrahedronDae(const std::string& up_axis) {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>)" +
         up_axis + R"(</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="12">0 0 0 100 0 0 0 200 0 0 0 300</float_array>
      <technique_common><accessor source="#pa" count="4" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="4"><input semantic="VERTEX" source="#v" offset="0"/><p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
}

TEST_CASE("DAE: <unit> is applied once and <up_axis> picks the default axes", "[import]") {
  TempDir dir;
  ImportReport report;
  // Y_UP: up +Y, forward +Z, so file z (3 m) is length, file y (2 m) height and file x (1 m) width.
  const deform::VehicleModel y_up =
      deform::loadVehicleModel(dir.write("y_up.dae", tetrahedronDae("Y_UP")), {}, report);
  CHECK(report.format == "DAE");
  CHECK(report.up == Axis::PosY);
  CHECK(report.forward == Axis::PosZ);
  CHECK(deform::boundingBox(y_up.body).size_m().isApprox(Eigen::Vector3d(3, 1, 2), 1e-6));
  CHECK(signedVolume(y_up.body) == Approx(1.0));  // 1 x 2 x 3 / 6, still wound outward
  // Z_UP: up +Z, forward +X: the file's axes are the vehicle's (assimp's own Y-up rotation is not applied
  // on top).
  const deform::VehicleModel z_up =
      deform::loadVehicleModel(dir.write("z_up.dae", tetrahedronDae("Z_UP")), {}, report);
  CHECK(report.up == Axis::PosZ);
  CHECK(report.forward == Axis::PosX);
  CHECK(deform::boundingBox(z_up.body).size_m().isApprox(Eigen::Vector3d(1, 2, 3), 1e-6));
  // Explicit axes refer to the file as written, whatever it declares.
  ImportOptions options;
  options.up = Axis::PosX;
  options.forward = Axis::NegY;
  const deform::VehicleModel turned =
      deform::loadVehicleModel(dir.write("z_up2.dae", tetrahedronDae("Z_UP")), options);
  CHECK(deform::boundingBox(turned.body).size_m().isApprox(Eigen::Vector3d(2, 3, 1), 1e-6));
}

TEST_CASE("FBX: UpAxis, FrontAxis and UnitScaleFactor from the file are applied", "[import]") {
  // A tetrahedron 1 x 2 x 3 file units along x, y, z; Z up, front -Y, 100 cm per unit (metres).
  const std::string fbx = R"(; FBX 7.4.0 project file
FBXHeaderExtension:  {
	FBXHeaderVersion: 1003
	FBXVersion: 7400
}
GlobalSettings:  {
	Version: 1000
	Properties70:  {
		P: "UpAxis", "int", "Integer", "",2
		P: "UpAxisSign", "int", "Integer", "",1
		P: "FrontAxis", "int", "Integer", "",1
		P: "FrontAxisSign", "int", "Integer", "",-1
		P: "CoordAxis", "int", "Integer", "",0
		P: "CoordAxisSign", "int", "Integer", "",1
		P: "UnitScaleFactor", "double", "Number", "",100
	}
}
Objects:  {
	Geometry: 1000, "Geometry::tet", "Mesh" {
		Vertices: *12 {
			a: 0,0,0,1,0,0,0,2,0,0,0,3
		}
		PolygonVertexIndex: *12 {
			a: 0,2,-2,0,1,-4,0,3,-3,1,2,-4
		}
		GeometryVersion: 124
	}
	Model: 2000, "Model::tet", "Mesh" {
		Version: 232
	}
}
Connections:  {
	C: "OO",2000,0
	C: "OO",1000,2000
}
)";
  TempDir dir;
  ImportReport report;
  const deform::VehicleModel model = deform::loadVehicleModel(dir.write("tet.fbx", fbx), {}, report);
  CHECK(report.format == "FBX");
  CHECK(report.up == Axis::PosZ);
  CHECK(report.forward == Axis::NegY);
  CHECK(report.file_unit_m == Approx(1.0));
  CHECK(report.raw_vertices == 12);  // assimp unshares FBX polygon corners; welding shares them again
  CHECK(model.body.positions_m.size() == 4);
  // Forward -Y: file y (2 m) runs backwards along vehicle X; left = up x forward = +X in the file.
  const deform::Aabb box = deform::boundingBox(model.body);
  CHECK(box.size_m().isApprox(Eigen::Vector3d(2, 1, 3), 1e-6));
  CHECK(box.min_m.x() == Approx(-2.0));
  CHECK(signedVolume(model.body) == Approx(1.0));
  // scale multiplies on top of the declared unit.
  ImportOptions half;
  half.scale = 0.5;
  CHECK(deform::boundingBox(deform::loadVehicleModel(dir.write("tet2.fbx", fbx), half).body)
            .size_m()
            .isApprox(Eigen::Vector3d(1, 0.5, 1.5), 1e-6));
}

TEST_CASE("loadVehicleModel refuses bad input with one message naming the file and the problem", "[import]") {
  TempDir dir;
  const auto expectError = [](const std::string& path, const ImportOptions& options,
                              const std::string& problem) {
    const std::string message = errorOf([&] { deform::loadVehicleModel(path, options); });
    INFO("message: " << message);
    CHECK(startsWith(message, path + ": "));
    CHECK(message.find(problem) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  };
  const std::string box = dir.write("box.obj", boxObj(1, 1, 1));

  SECTION("missing file") {
    expectError((dir.path / "nothere.obj").string(), {}, "file not found");
  }
  SECTION("a directory") {
    expectError(dir.path.string(), {}, "directory");
  }
  SECTION("garbage in an unknown format") {
    expectError(dir.write("garbage.xyz", std::string("\x01\x02garbage\xff\xfe not a mesh\n", 24)), {},
                "cannot read");
  }
  SECTION("garbage behind a known extension") {
    expectError(dir.write("garbage.glb", "glTF? no, just some text that is not a binary glTF\n"), {},
                "cannot read");
  }
  SECTION("only points and lines") {
    expectError(dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\nl 1 2\nl 2 3\n"), {}, "no triangles");
  }
  SECTION("vertices but no faces") {
    expectError(dir.write("cloud.obj", "# a point cloud\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"), {},
                "no triangles");
  }
  SECTION("an empty file") {
    expectError(dir.write("empty.obj", ""), {}, "cannot read");
  }
  SECTION("a NaN coordinate") {
    expectError(dir.write("nan.ply",
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                          "end_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
                {}, "non-finite");
  }
  SECTION("an infinite coordinate") {
    expectError(dir.write("inf.ply",
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                          "end_header\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n"),
                {}, "non-finite");
  }
  SECTION("a PLY header without end_header (assimp 5.2.4 reads it forever; found by fuzz_mesh_ply)") {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n";
    expectError(dir.write("no_end_header.ply", header), {}, "without an end_header line");
    expectError(dir.write("ply_content.stl", header + "element face 4\npropert2 3\n"), {},
                "without an end_header line");
    // "ply" and no line break at all: assimp still takes it for PLY, and read it for over 2.5 min of CPU
    // (still going) before this check (regressions/mesh_ply/assimp_hang_ply_signature_without_newline.ply).
    expectError(
        dir.write("signature.ply", std::string("ply>333\x01\x02\xff\xff\x3f") + std::string(200, '\x3f')), {},
        "without an end_header line");
  }
  SECTION("a file on which assimp aborts (an assertion in its triangulation; found by fuzz_mesh_ply)") {
    // The import runs in a child process: the abort ends the child, the file is refused, and this
    // process imports the next file as before.
    const std::string crash = std::string(DEFORM_SOURCE_DIR) +
                              "/tests/fuzz/regressions/mesh_ply/assimp_abort_triangulate_face_count.ply";
    expectError(crash, {}, "the importer (assimp) crashed on this file (signal 6");
    expectError(crash, {}, "ai_assert failure");  // assimp's own line, in the one message
    CHECK(deform::loadVehicleModel(box).body.triangles.size() == 12);
  }
  SECTION("zero extent") {
    expectError(dir.write("point.obj", "v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3\n"), {}, "zero extent");
  }
  SECTION("a scale that overflows float") {
    ImportOptions options;
    options.scale = 1e300;
    expectError(box, options, "non-finite");
  }
  SECTION("scale zero, negative or not a number") {
    for (double scale :
         {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      ImportOptions options;
      options.scale = scale;
      expectError(box, options, "scale");
    }
  }
  SECTION("up parallel to forward") {
    ImportOptions options;
    options.up = Axis::PosY;
    options.forward = Axis::PosY;
    expectError(box, options, "perpendicular");
    options.forward = Axis::NegY;
    expectError(box, options, "perpendicular");
    ImportOptions only_up;  // OBJ's default forward is +X
    only_up.up = Axis::NegX;
    expectError(box, only_up, "perpendicular");
  }
}

TEST_CASE("loadVehicleModel delegates builtin: specs and applies scale and axes only when given",
          "[import]") {
  const deform::VehicleModel plain = deform::makeBuiltin("builtin:box?x=4&y=2&z=1");
  ImportReport report;
  const deform::VehicleModel loaded = deform::loadVehicleModel("builtin:box?x=4&y=2&z=1", {}, report);
  CHECK(report.format == "builtin");
  CHECK(loaded.source == "builtin:box?x=4&y=2&z=1");
  REQUIRE(loaded.body.positions_m.size() == plain.body.positions_m.size());
  CHECK(loaded.body.positions_m == plain.body.positions_m);

  ImportOptions options;
  options.scale = 2;
  options.up = Axis::PosY;  // the box's Y (2 m) becomes height
  const deform::VehicleModel turned = deform::loadVehicleModel("builtin:box?x=4&y=2&z=1", options);
  CHECK(deform::boundingBox(turned.body).size_m().isApprox(Eigen::Vector3d(8, 2, 4), 1e-5));

  const std::string message = errorOf([] { deform::loadVehicleModel("builtin:nonsense"); });
  CHECK(startsWith(message, "builtin:nonsense: "));
}

namespace {

/// One shared mesh, the options that bring it to real-world size, and what that size must be.
struct SharedMesh {
  const char* file;  ///< under DEFORM_TEST_MESHES
  ImportOptions options;
  double min_length_m, max_length_m;  ///< along X
  double min_height_m, max_height_m;  ///< along Z
  bool longest_along_x;               ///< a vehicle or barrier: X is its longest horizontal extent
};

ImportOptions opts(double scale, std::optional<Axis> up = {}, std::optional<Axis> forward = {},
                   bool root_transform = true) {
  ImportOptions o;
  o.scale = scale;
  o.up = up;
  o.forward = forward;
  o.root_transform = root_transform;
  return o;
}

}  // namespace

TEST_CASE("every shared mesh loads upright, along +X, at real-world size", "[import]") {
  const std::optional<std::string> meshes = test_support::testMeshesDir();
  if (!meshes) {
    test_support::reportSkip("DEFORM_TEST_MESHES is not set: the shared third-party meshes are not loaded");
    return;
  }
  const SharedMesh cases[] = {
      // Gazebo hatchback: inches (model.sdf scale 0.0254), Z up, front wheels at file -Y.
      {"gazebo_hatchback/meshes/hatchback.obj", opts(0.0254, {}, Axis::NegY), 3.5, 4.5, 1.3, 1.7, true},
      // Gazebo pickup: <unit> inch (applied by assimp), Z_UP, faces file +Y (mirrors at the cab's front).
      {"gazebo_pickup/meshes/pickup.dae", opts(1.0, {}, Axis::PosY), 5.0, 6.0, 1.6, 2.1, true},
      // Gazebo coke can: <unit> millimetre, Y_UP: 0.067 m wide, 0.124 m tall.
      {"gazebo_coke_can/meshes/coke_can.dae", opts(1.0), 0.06, 0.075, 0.115, 0.13, false},
      // Gazebo jersey barrier: <unit> inch, Z_UP, 4.07 m long along file X.
      {"gazebo_jersey_barrier/meshes/jersey_barrier.dae", opts(1.0), 3.9, 4.2, 1.0, 1.3, true},
      // Gazebo lamp post: <unit> inch gives 3.09 m; model.sdf scales it by 3 to a 9.3 m street light.
      {"gazebo_lamp_post/meshes/lamp_post.dae", opts(3.0), 0.3, 0.7, 8.5, 10.0, false},
      // Godot truck town: five vehicles at one origin (glTF defaults), the trailer is the longest.
      {"godot_truck_town_vehicles/meshes.glb", opts(1.0), 3.8, 4.6, 1.5, 2.2, true},
      // CesiumMilkTruck (ramses-composer copy): its root "Yup2Zup" node holds an arbitrary rotation, so
      // drop it; the truck node is then -Z up, +X forward.
      {"khronos_CesiumMilkTruck/CesiumMilkTruck.gltf", opts(1.0, Axis::NegZ, Axis::PosX, false), 4.5, 5.5,
       2.3, 2.9, true},
      // ToyCar: node transforms scale it by 1e-4 to a toy of a few cm on a 7 cm cloth (glTF defaults).
      {"khronos_ToyCar/ToyCar.gltf", opts(1.0), 0.06, 0.09, 0.02, 0.04, false},
      // Bullet racecar chassis: metres (the urdf places it unscaled; wheels of radius 0.05 m).
      {"bullet_racecar/meshes/chassis.STL", opts(1.0), 0.35, 0.45, 0.04, 0.08, true},
  };
  for (const SharedMesh& c : cases) {
    const std::string path = *meshes + "/" + c.file;
    INFO(c.file);
    ImportReport report;
    const deform::VehicleModel model = deform::loadVehicleModel(path, c.options, report);
    const Eigen::Vector3d size = deform::boundingBox(model.body).size_m();
    INFO("size " << size.transpose() << " m, " << model.body.positions_m.size() << " vertices (raw "
                 << report.raw_vertices << "), " << model.body.triangles.size() << " triangles");
    CHECK(report.merged_vertices > 0);
    CHECK(model.body.positions_m.size() < report.raw_vertices);
    CHECK(model.body.normals.size() == model.body.positions_m.size());
    CHECK(size.x() >= c.min_length_m);
    CHECK(size.x() <= c.max_length_m);
    CHECK(size.z() >= c.min_height_m);
    CHECK(size.z() <= c.max_height_m);
    if (c.longest_along_x) CHECK(size.x() > size.y());
  }
}

TEST_CASE("shared meshes: units and axes the format declares are honoured", "[import]") {
  const std::optional<std::string> meshes = test_support::testMeshesDir();
  if (!meshes) {
    test_support::reportSkip("DEFORM_TEST_MESHES is not set: the shared third-party meshes are not loaded");
    return;
  }
  // The pickup declares Z_UP and inches: without options it is upright, in metres, lying along file Y.
  ImportReport report;
  const deform::VehicleModel pickup =
      deform::loadVehicleModel(*meshes + "/gazebo_pickup/meshes/pickup.dae", {}, report);
  CHECK(report.up == Axis::PosZ);
  CHECK(report.forward == Axis::PosX);
  const Eigen::Vector3d size = deform::boundingBox(pickup.body).size_m();
  CHECK(size.z() == Approx(1.87).margin(0.02));
  CHECK(size.y() == Approx(5.66).margin(0.02));
  // The coke can says Y_UP, but MeshLab wrote it and MeshLab always says Y_UP: the can stands on file Z.
  const deform::VehicleModel can =
      deform::loadVehicleModel(*meshes + "/gazebo_coke_can/meshes/coke_can.dae", {}, report);
  CHECK(report.up == Axis::PosZ);
  CHECK(report.forward == Axis::PosX);
  CHECK(deform::boundingBox(can.body).size_m().z() == Approx(0.124).margin(0.001));
  // Instanced wheels of the milk truck: the wheel mesh is placed by two nodes, one of them scaled to zero
  // on one axis in this copy (skipped), so one instance of it plus the three body parts.
  deform::loadVehicleModel(*meshes + "/khronos_CesiumMilkTruck/CesiumMilkTruck.gltf",
                           opts(1.0, Axis::NegZ, Axis::PosX, false), report);
  CHECK(report.mesh_instances == 4);
  CHECK(report.skipped_instances == 1);
}
