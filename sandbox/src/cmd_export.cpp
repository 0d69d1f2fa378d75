// `sandbox export SCENE --at T --out FILE.glb|.obj [--frame vehicle|world]`: the damaged car at time T as a
// mesh (assimp's exporter), wheels at their rest hubs, to open in any 3D tool: in the vehicle frame, or
// the same mesh placed rigidly at the car's world pose at T (to put beside the scene's obstacles).
#include <deform/mesh_export.hpp>
#include <deform/path_checks.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "run_command.hpp"
#include "run_render.hpp"

namespace fs = std::filesystem;

namespace sandbox {

void exportScene(const ExportOptions& options) {
  const std::string extension = fs::path(options.out).extension().string();
  if (extension != ".glb" && extension != ".obj") {
    throw deform::InputError("--out: " + options.out + ": give a .glb or .obj file");
  }
  if (options.frame != "vehicle" && options.frame != "world") {
    throw deform::InputError("--frame: must be vehicle or world (got '" + options.frame + "')");
  }
  const fs::path parent = fs::path(options.out).parent_path();
  if (!parent.empty() && !deform::isDirectory(parent)) {
    throw deform::InputError("--out: folder " + parent.string() + " does not exist");
  }
  std::vector<scenes::Override> overrides;
  for (const std::string& s : options.sets) overrides.push_back(scenes::parseOverride(s));
  const scenes::SceneConfig scene = scenes::loadScene(options.scene, overrides);
  if (!(options.at_s >= 0 && options.at_s <= scene.duration_s)) {
    throw deform::InputError("--at: must be in [0, " + std::to_string(scene.duration_s) +
                             "] s (the scene's duration_s)");
  }
  if (options.car >= scene.vehicles.size()) {
    throw deform::InputError("--car: the scene has " + std::to_string(scene.vehicles.size()) + " car(s)");
  }
  scenes::SceneRun run(scene);
  run.stepUntil(options.at_s);
  deform::Mesh mesh = deformedBody(run, options.car);
  for (const deform::WheelPart& wheel : run.model(options.car).wheels) {
    deform::Mesh tyre = deform::makeWheelMesh(wheel.radius_m, wheel.width_m);
    for (Eigen::Vector3f& p : tyre.positions_m) p += wheel.centre_m.cast<float>();
    deform::appendMesh(mesh, tyre);
  }
  const vehicle::Pose pose = run.simulation().world().car(run.carId(options.car)).vehiclePose();
  if (options.frame == "world") {
    for (Eigen::Vector3f& p : mesh.positions_m) p = pose.toWorld(p.cast<double>()).cast<float>();
  }
  deform::computeVertexNormals(mesh);
  deform::exportMesh(mesh, options.out);
  std::printf(
      "wrote %s: %s at t = %.3f s (%llu steps), %zu vertices, %zu triangles, %s frame; state hash %s\n",
      options.out.c_str(), scene.vehicles[options.car].name.c_str(), run.time_s(),
      static_cast<unsigned long long>(run.steps()), mesh.positions_m.size(), mesh.triangles.size(),
      options.frame.c_str(), scenes::hashHex(run.simulation().stateHash()).c_str());
  const Eigen::Quaterniond& q = pose.orientation;
  std::printf(
      "vehicle pose: origin (%.6f, %.6f, %.6f) m, orientation (w, x, y, z) (%.9f, %.9f, %.9f, %.9f)\n",
      pose.position_m.x(), pose.position_m.y(), pose.position_m.z(), q.w(), q.x(), q.y(), q.z());
}

void registerExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  auto* cmd = app.add_subcommand("export", "Write the damaged car at time T as a mesh (.glb or .obj)");
  cmd->add_option("SCENE", options->scene, "Scene file, or a shipped scene's name")->required();
  cmd->add_option("--at", options->at_s, "Simulated time of the snapshot [s]")->required();
  cmd->add_option("--out", options->out, "Mesh file to write: .glb (binary glTF, Y up) or .obj (Z up)")
      ->required();
  cmd->add_option("--car", options->car, "Which car of the scene (0 = the first)")->capture_default_str();
  cmd->add_option("--frame", options->frame,
                  "vehicle: the car's own frame; world: placed at the car's pose at --at")
      ->capture_default_str();
  cmd->add_option("--set", options->sets,
                  "Override a scene key: --set vehicle.start.speed_kmh=5 (repeatable)")
      ->expected(1)
      ->take_all();
  cmd->callback([options] { exportScene(*options); });
}

}  // namespace sandbox
