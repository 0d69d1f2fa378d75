#include <deform/control_mesh.hpp>
#include <deform/error.hpp>
#include <deform/mesh_import.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "mesh_options.hpp"
#include "mesh_report.hpp"

namespace sandbox {
namespace {

struct MeshInfoFlags {
  std::string mesh;
  MeshLoadFlags load;
  std::size_t control_points = 60;
  std::string lod = "even";
  double alpha = 3.5;
  std::size_t k = 8;
  std::string skin_method = "auto";
  double mass_kg = 1500;
  unsigned threads = 0;
  bool json = false;
};

void runMeshInfo(const MeshInfoFlags& flags) {
  if (flags.control_points < 4) throw deform::InputError("--control-points: must be at least 4");
  if (!(flags.alpha > 0 && flags.alpha <= 64)) throw deform::InputError("--alpha: must be in (0, 64]");
  if (flags.k > 65536) throw deform::InputError("--k: at most 65536 (0 means dense)");
  if (!(std::isfinite(flags.mass_kg) && flags.mass_kg > 0))
    throw deform::InputError("--mass-kg: must be above zero");
  MeshReportOptions options;
  options.control_points = flags.control_points;
  options.lod = deform::parseLodMethod(flags.lod, "--lod");
  options.vehicle_mass_kg = flags.mass_kg;
  options.skin = {flags.alpha, flags.k, flags.threads,
                  deform::preferredSkinMethod(flags.control_points, flags.k)};
  if (flags.skin_method != "auto" && !deform::parseSkinMethod(flags.skin_method, options.skin.method))
    throw deform::InputError("--skin-method: must be auto, idw, mls or spline (got '" + flags.skin_method +
                             "')");
  // Every flag checked before the mesh is loaded (a large file takes seconds).
  const deform::VehicleModel model = deform::loadVehicleModel(flags.mesh, flags.load.importOptions());
  const auto report = meshReport(model, options);
  if (flags.json)
    std::printf("%s\n", report.dump(2).c_str());
  else
    std::printf("%s", formatMeshReport(report).c_str());
}

}  // namespace

void registerMeshCommands(CLI::App& app) {
  auto* mesh = app.add_subcommand("mesh", "Inspect a mesh, its control mesh and its embedding");
  mesh->require_subcommand(1);

  auto flags = std::make_shared<MeshInfoFlags>();
  auto* info =
      mesh->add_subcommand("info", "Sizes, convex hull, control mesh, mass split and embedding checks");
  info->add_option("MESH", flags->mesh, "builtin:sedan[?vertices=N], builtin:can, builtin:box or a mesh file")
      ->required();
  flags->load.addTo(*info);
  info->add_option("--control-points", flags->control_points, "Control points N (level of detail)")
      ->capture_default_str();
  info->add_option("--lod", flags->lod,
                   "Level-of-detail method: even (spread over the hull) or simplify (meshoptimizer)")
      ->capture_default_str();
  info->add_option("--alpha", flags->alpha, "Inverse-distance power of the embedding")->capture_default_str();
  info->add_option("--k", flags->k, "Influences per vertex (0 = dense)")->capture_default_str();
  info->add_option("--skin-method", flags->skin_method,
                   "Skin weights: auto (mls up to 60 control points, idw above: the better measured), idw "
                   "(inverse distance, the paper's) or mls (moving least squares, affine maps exact)")
      ->capture_default_str();
  info->add_option("--mass-kg", flags->mass_kg, "Vehicle mass [kg]")->capture_default_str();
  info->add_option("--threads", flags->threads, "Worker threads (0 = all cores)")->capture_default_str();
  info->add_flag("--json", flags->json, "Print one JSON object");
  info->callback([flags] { runMeshInfo(*flags); });

  registerMeshRenderCommand(*mesh);
}

}  // namespace sandbox
