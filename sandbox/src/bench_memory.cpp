// `sandbox bench memory` (issue 13): the bytes a car costs, per control point and per render vertex, for
// the shared body settings, each car's state and each car's skin, measured as heap growth (glibc's
// mallinfo2) while `cars` cars of one model are made, and the process's resident set (/proc/self/statm)
// at the end: what a scene of that many cars would hold before ODE and the renderer.
#include <deform/body_settings.hpp>
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/deformable_body.hpp>
#include <deform/error.hpp>
#include <deform/masses.hpp>
#include <scenes/car_skin.hpp>
#include "resident_memory.hpp"

#include <malloc.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace sandbox {
namespace {

struct BenchMemoryFlags {
  std::size_t cars = 100;
  std::size_t control_points = 60;
  std::size_t vertices = 20000;
  bool json = false;
};

double heapBytes() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd);  // in use: small blocks + mmapped ones
}

void runBenchMemory(const BenchMemoryFlags& f) {
  if (f.cars < 1) throw deform::InputError("--cars: at least 1");
  if (f.control_points < 4) throw deform::InputError("--control-points: at least 4");
  if (f.vertices < 1000) throw deform::InputError("--vertices: at least 1000");
  const double rss_start = residentBytes();
  const deform::VehicleModel car = deform::makeSedan(f.vertices);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : car.body.positions_m) points.push_back(p.cast<double>());
  const deform::ControlMesh mesh = deform::buildControlMesh(points, f.control_points, "builtin:sedan");
  const std::size_t n = mesh.points_m.size(), v = car.body.positions_m.size();

  double before = heapBytes();
  const auto settings = std::make_shared<const deform::BodySettings>(
      deform::createBodySettings(mesh, deform::distributeMass(mesh, 1500), deform::BodyDescription{}));
  const double settings_bytes = heapBytes() - before;

  // Each car's state: a body stepped once (its scratch arrays allocated), free of contact.
  before = heapBytes();
  std::vector<std::unique_ptr<deform::DeformableBody>> bodies;
  for (std::size_t c = 0; c < f.cars; ++c) {
    bodies.push_back(std::make_unique<deform::DeformableBody>(settings));
    bodies.back()->step(deform::StepInputs{}, 1.0 / 60);
  }
  const double state_bytes = (heapBytes() - before) / static_cast<double>(f.cars);

  // The skin as the scenes hold it: one shared build for the model (scenes::CarSkin::Build: weights,
  // rest copy, triangles, the triangles around each vertex, the vertex grid of the contact projection),
  // then each car's own part (deformed positions and normals, flags), updated once.
  before = heapBytes();
  vehicle::DeformationSettings deformation;
  const std::shared_ptr<const scenes::CarSkin::Build> build =
      scenes::CarSkin::share(car.body, scenes::CarSkin::buildSkin(car.body, mesh.points_m, deformation));
  const double shared_skin_bytes = heapBytes() - before;
  before = heapBytes();
  std::vector<std::unique_ptr<scenes::CarSkin>> skins;
  std::vector<Eigen::Vector3d> displacement(n, Eigen::Vector3d(0.01, 0, 0));
  for (std::size_t c = 0; c < f.cars; ++c) {
    skins.push_back(std::make_unique<scenes::CarSkin>(build));
    skins.back()->update(displacement);
  }
  const double skin_bytes = (heapBytes() - before) / static_cast<double>(f.cars);
  const deform::Skin& weights = skins.front()->skin();
  const double rss_end = residentBytes();

  nlohmann::ordered_json r;
  r["cars"] = f.cars;
  r["control_points"] = n;
  r["vertices"] = v;
  r["settings_bytes"] = settings_bytes;
  r["settings_bytes_per_control_point"] = settings_bytes / static_cast<double>(n);
  r["state_bytes_per_car"] = state_bytes;
  r["state_bytes_per_control_point"] = state_bytes / static_cast<double>(n);
  r["skin_shared_bytes"] = shared_skin_bytes;
  r["skin_shared_bytes_per_vertex"] = shared_skin_bytes / static_cast<double>(v);
  r["skin_bytes_per_car"] = skin_bytes;
  r["skin_bytes_per_vertex"] = skin_bytes / static_cast<double>(v);
  r["skin_weights_bytes_per_vertex"] = static_cast<double>(weights.memoryBytes()) / static_cast<double>(v);
  r["skin_reverse_index_bytes_per_vertex"] =
      static_cast<double>(weights.reverseIndexBytes()) / static_cast<double>(v);
  r["rss_start_bytes"] = rss_start;
  r["rss_end_bytes"] = rss_end;
  r["fits_200_MB"] = rss_end < 200e6;
  if (f.json) {
    std::printf("%s\n", r.dump(2).c_str());
    return;
  }
  std::printf("memory: %zu cars of %zu control points and %zu render vertices (builtin:sedan)\n", f.cars, n,
              v);
  std::printf("  body settings (shared)  %9.0f B  = %6.0f B per control point\n", settings_bytes,
              settings_bytes / static_cast<double>(n));
  std::printf("  state, per car          %9.0f B  = %6.0f B per control point\n", state_bytes,
              state_bytes / static_cast<double>(n));
  std::printf(
      "  skin build (shared)     %9.0f B  = %6.1f B per render vertex (weights %.1f, reverse index %.1f)\n",
      shared_skin_bytes, shared_skin_bytes / static_cast<double>(v),
      static_cast<double>(weights.memoryBytes()) / static_cast<double>(v),
      static_cast<double>(weights.reverseIndexBytes()) / static_cast<double>(v));
  std::printf("  skin, per car           %9.0f B  = %6.1f B per render vertex\n", skin_bytes,
              skin_bytes / static_cast<double>(v));
  std::printf("  resident set            %.1f MB at the start, %.1f MB with every car (%s 200 MB)\n",
              rss_start / 1e6, rss_end / 1e6, rss_end < 200e6 ? "under" : "OVER");
}

}  // namespace

void registerBenchMemoryCommand(CLI::App& bench) {
  auto flags = std::make_shared<BenchMemoryFlags>();
  auto* memory = bench.add_subcommand(
      "memory", "Bytes per control point and per render vertex, and the RSS of many cars");
  memory->add_option("--cars", flags->cars, "Cars of one model")->capture_default_str();
  memory->add_option("--control-points", flags->control_points, "Control points N")->capture_default_str();
  memory->add_option("--vertices", flags->vertices, "Render-mesh vertices of builtin:sedan")
      ->capture_default_str();
  memory->add_flag("--json", flags->json, "Print one JSON object");
  memory->callback([flags] { runBenchMemory(*flags); });
}

}  // namespace sandbox
