// `sandbox mesh render`: one offscreen picture of a vehicle mesh on the ground, optionally coloured by
// one control point's influence (the paper's embedding figure).
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>
#include <deform/mesh_import.hpp>
#include <deform/path_checks.hpp>
#include <deform/skin.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "mesh_options.hpp"
#include "render/colour_ramp.hpp"
#include "render/marker.hpp"
#include "render/renderer.hpp"
#include "render/vehicle_meshes.hpp"

namespace sandbox {
namespace {

struct MeshRenderFlags {
  std::string mesh;
  MeshLoadFlags load;
  std::string out;
  int width = 1280;
  int height = 720;
  std::string camera = "quarter";
  std::optional<uint32_t> heatmap_point;
  std::size_t control_points = 60;
  double alpha = 3.5;
  std::size_t k = 8;
  int samples = 4;
  int timing_frames = 0;
};

// Colours every body vertex by the weight control point `point` has on it, scaled so the largest weight
// is red: weights of hull points that sit off the surface never reach 1, and the ramp should be used.
// The control point itself is returned in `point_m`, to be marked.
std::vector<Eigen::Vector3f> influenceColours(const deform::Mesh& body, const MeshRenderFlags& flags,
                                              uint32_t point, Eigen::Vector3f& point_m) {
  std::vector<Eigen::Vector3d> points(body.positions_m.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = body.positions_m[i].cast<double>();
  const deform::ControlMesh control =
      deform::buildControlMesh(points, flags.control_points, flags.mesh.c_str());
  if (point >= control.points_m.size()) {
    throw deform::InputError("--heatmap-point: " + std::to_string(point) +
                             " is not a control point (the mesh has " +
                             std::to_string(control.points_m.size()) + ", numbered from 0)");
  }
  const deform::Skin skin =
      deform::Skin::build(body.positions_m, control.points_m, {flags.alpha, flags.k, 0});
  std::vector<float> weights(body.positions_m.size());
  float largest = 0.0f;
  for (std::size_t j = 0; j < weights.size(); ++j) {
    weights[j] = skin.weight(j, point);
    largest = std::max(largest, weights[j]);
  }
  point_m = control.points_m[point].cast<float>();
  std::vector<Eigen::Vector3f> colours(weights.size());
  for (std::size_t j = 0; j < weights.size(); ++j) {
    colours[j] = render::heatColour(largest > 0.0f ? weights[j] / largest : 0.0f);
  }
  std::printf("control point %u of %zu at (%.3f, %.3f, %.3f) m, largest weight %.3f (shown red)\n", point,
              control.points_m.size(), control.points_m[point].x(), control.points_m[point].y(),
              control.points_m[point].z(), static_cast<double>(largest));
  return colours;
}

void runMeshRender(const MeshRenderFlags& flags) {
  if (flags.width < 2 || flags.width > 8192) throw deform::InputError("--width: must be 2..8192 pixels");
  if (flags.height < 2 || flags.height > 8192) throw deform::InputError("--height: must be 2..8192 pixels");
  if (flags.samples < 0 || flags.samples > 16) throw deform::InputError("--samples: must be 0..16");
  if (flags.control_points < 4) throw deform::InputError("--control-points: must be at least 4");
  if (!(flags.alpha > 0 && flags.alpha <= 64)) throw deform::InputError("--alpha: must be in (0, 64]");
  const std::filesystem::path out(flags.out);
  if (out.has_parent_path() && !deform::isDirectory(out.parent_path())) {
    throw deform::InputError("--out: folder " + out.parent_path().string() + " does not exist");
  }
  if (deform::isDirectory(out)) throw deform::InputError("--out: " + flags.out + " is a folder");
  const float aspect = static_cast<float>(flags.width) / static_cast<float>(flags.height);
  render::presetCamera(flags.camera, deform::Aabb{{-1, -1, -1}, {1, 1, 1}}, aspect);  // name check first

  const deform::VehicleModel model = deform::loadVehicleModel(flags.mesh, flags.load.importOptions());
  std::vector<render::MeshData> meshes = render::vehicleMeshes(model);
  if (flags.heatmap_point) {
    Eigen::Vector3f point_m;
    meshes.front().colours = influenceColours(model.body, flags, *flags.heatmap_point, point_m);
    meshes.front().specular = 0.2f;  // a glossy highlight would read as a colour of the ramp
    // A dark bead on the control point (which sits on the hull, possibly off the surface).
    const float radius = 0.012f * static_cast<float>(deform::boundingBox(model.body).diagonal_m());
    meshes.push_back(render::markerSphere(point_m, radius, {0.05f, 0.05f, 0.05f}));
  }

  const auto start = std::chrono::steady_clock::now();
  render::Renderer renderer({flags.width, flags.height, flags.samples});
  for (const render::MeshData& mesh : meshes) renderer.addMesh(mesh);
  const auto uploaded = std::chrono::steady_clock::now();
  const deform::Aabb box = render::vehicleBounds(model);
  const render::Image image =
      renderer.renderImage(render::presetCamera(flags.camera, box, aspect), render::environmentAround(box));
  const auto rendered = std::chrono::steady_clock::now();
  render::writePng(flags.out, image.width, image.height, image.rgba);
  const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  std::printf(
      "wrote %s: %dx%d, %zu body vertices, %zu wheels, %s camera; set-up %.0f ms, frame %.0f ms (%s)\n",
      flags.out.c_str(), image.width, image.height, model.body.positions_m.size(), model.wheels.size(),
      flags.camera.c_str(), ms(start, uploaded), ms(uploaded, rendered), renderer.description().c_str());
  // The first frame includes compiling the shaders to machine code (llvmpipe does it at first draw);
  // later frames of a video cost what these repeats cost.
  if (flags.timing_frames > 0) {
    const auto camera = render::presetCamera(flags.camera, box, aspect);
    const auto environment = render::environmentAround(box);
    const auto timing_start = std::chrono::steady_clock::now();
    for (int i = 0; i < flags.timing_frames; ++i) {
      renderer.updatePositions(0, meshes.front().positions_m, meshes.front().normals);  // as a deforming body
      (void)renderer.renderImage(camera, environment);
    }
    const double each =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - timing_start).count() /
        flags.timing_frames;
    std::printf("%d more frames (upload positions + normals, render, read back): %.1f ms each\n",
                flags.timing_frames, each);
  }
}

}  // namespace

void registerMeshRenderCommand(CLI::App& mesh) {
  auto flags = std::make_shared<MeshRenderFlags>();
  auto* render = mesh.add_subcommand("render", "Offscreen picture (PNG) of a mesh on the ground");
  render
      ->add_option("MESH", flags->mesh, "builtin:sedan[?vertices=N], builtin:can, builtin:box or a mesh file")
      ->required();
  flags->load.addTo(*render);
  render->add_option("--out", flags->out, "PNG file to write")->required();
  render->add_option("--width", flags->width, "Picture width [px]")->capture_default_str();
  render->add_option("--height", flags->height, "Picture height [px]")->capture_default_str();
  render->add_option("--camera", flags->camera, "View: side, chase, front, top or quarter")
      ->capture_default_str();
  render->add_option("--heatmap-point", flags->heatmap_point,
                     "Colour the body by this control point's influence (blue none .. red most)");
  render->add_option("--control-points", flags->control_points, "Control points N for --heatmap-point")
      ->capture_default_str();
  render->add_option("--alpha", flags->alpha, "Inverse-distance power for --heatmap-point")
      ->capture_default_str();
  render->add_option("--k", flags->k, "Influences per vertex for --heatmap-point (0 = dense)")
      ->capture_default_str();
  render->add_option("--samples", flags->samples, "Multisampling per pixel (0 = off)")->capture_default_str();
  render->add_option("--timing-frames", flags->timing_frames,
                     "Render this many more frames and print the time per frame (for benchmarks)");
  render->callback([flags] { runMeshRender(*flags); });
}

}  // namespace sandbox
