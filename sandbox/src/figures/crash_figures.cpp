// The paper's crash figures: a scene played with our runner, the render mesh following the control
// points, coloured by how far each vertex moved for good (red most, blue none).
#include <deform/heat_colours.hpp>
#include <scenes/car_skin.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <cstdio>
#include <filesystem>

#include "figures.hpp"
#include "image_tiles.hpp"
#include "render/renderer.hpp"
#include "render/vehicle_meshes.hpp"

#include "run_render.hpp"

namespace sandbox::figures {
namespace {

struct DentedCar {
  deform::VehicleModel model;                    ///< the car as loaded, undamaged
  deform::Mesh dented;                           ///< its body after the scene (vehicle frame)
  std::vector<deform::WheelPart> dented_wheels;  ///< its wheels, carried with the bodywork around them
  std::vector<Eigen::Vector3f> colours;          ///< permanent displacement, blue none .. red most
  vehicle::CrashMetrics metrics;
  std::size_t control_points = 0;
};

/// Plays `scene` (with `overrides`) to its end and dents car 0's render mesh by its control points.
DentedCar playAndDent(const std::string& scene, const std::vector<std::string>& overrides) {
  std::vector<scenes::Override> parsed;
  for (const auto& o : overrides) parsed.push_back(scenes::parseOverride(o));
  scenes::SceneRun run(scenes::loadScene(scene, parsed));
  run.runToEnd();
  const auto& sim = run.simulation();
  const vehicle::CarId id = run.carId(0);
  scenes::CarSkin skin(run.model(0).body, sim.controlRestPoints(id), sim.deformationSettings(id));
  skin.update(sim.controlDisplacements(id));
  DentedCar car;
  car.model = run.model(0);
  car.dented = skin.mesh();
  // The wheels carried with the bodywork around them (as in the crash videos).
  std::vector<Eigen::Vector3f> hubs;
  for (const auto& w : car.model.wheels) hubs.push_back(w.centre_m.cast<float>());
  car.dented_wheels = car.model.wheels;
  if (!hubs.empty()) {
    const vehicle::DeformationSettings& d = sim.deformationSettings(id);
    const deform::Skin hub_skin =
        deform::Skin::build(hubs, sim.controlRestPoints(id), deform::SkinOptions{d.alpha, d.k_nearest, 1});
    const auto shifts = embeddedShifts_m(hub_skin, hubs, sim.controlDisplacements(id));
    for (std::size_t k = 0; k < shifts.size(); ++k) car.dented_wheels[k].centre_m += shifts[k];
  }
  car.colours = deform::displacementColours(skin.restPositions(), car.dented.positions_m);
  car.metrics = sim.metrics(id);
  car.control_points = sim.controlRestPoints(id).size();
  return car;
}

/// The dented car, standing on the ground, from several named views.
std::vector<render::Image> views(const DentedCar& car, const FigureOptions& o,
                                 const std::vector<std::string>& cameras) {
  render::RenderSettings settings;
  settings.width = o.panel_width;
  settings.height = o.panel_height;
  settings.samples = o.samples;
  render::Renderer renderer(settings);
  deform::VehicleModel dented = car.model;
  dented.body = car.dented;
  dented.wheels = car.dented_wheels;
  const auto meshes = render::vehicleMeshes(dented, {0.75f, 0.08f, 0.06f});
  const auto body = renderer.addMesh(meshes.front());
  for (std::size_t i = 1; i < meshes.size(); ++i) renderer.addMesh(meshes[i]);
  renderer.setColours(body, car.colours);
  const deform::Aabb box = render::vehicleBounds(car.model);
  const render::Environment environment = render::environmentAround(box);
  std::vector<render::Image> images;
  for (const auto& name : cameras)
    images.push_back(renderer.renderImage(render::presetCamera(name, box, renderer.aspect()), environment));
  return images;
}

void save(const FigureOptions& o, const std::string& file, const render::Image& image) {
  std::filesystem::create_directories(o.out_dir);
  render::writePng((std::filesystem::path(o.out_dir) / file).string(), image.width, image.height, image.rgba);
}

}  // namespace

Figure wallCrashFigure(const FigureOptions& o) {
  const DentedCar car = playAndDent("wall_crash", {});
  save(o, "wall_crash.png", tileImages(views(car, o, {"quarter", "side", "top"}), 3));
  char caption[640];
  std::snprintf(
      caption, sizeof caption,
      "`sandbox run wall_crash`: the built-in sedan (%zu vertices, %zu control points, crush coupling) "
      "into a rigid wall at %.1f km/h, after the rebound; coloured by permanent displacement (red "
      "%.2f m, blue none). Residual crush %.3f m averaged over six stations (largest %.3f m), "
      "restitution %.2f, plastic work %.0f kJ of %.0f kJ.",
      car.dented.positions_m.size(), car.control_points, 3.6 * car.metrics.impact_speed_mps,
      car.metrics.max_deviation_m, car.metrics.residual_crush_m, car.metrics.max_residual_crush_m,
      car.metrics.restitution, car.metrics.energy.plastic_work_J / 1e3,
      car.metrics.energy.kinetic_initial_J / 1e3);
  return {"wall_crash.png", caption};
}

Figure minorHitsFigure(const FigureOptions& o) {
  // post_bumps as shipped (a tree, a shrub, then a bollard) with the 900,000-vertex car.
  const DentedCar car = playAndDent("post_bumps", {"vehicle.mesh=\"builtin:sedan?vertices=900000\"",
                                                   "vehicle.deformation.control_points=60"});
  save(o, "minor_hits.png", tileImages(views(car, o, {"quarter", "front"}), 2));
  char caption[720];
  std::snprintf(
      caption, sizeof caption,
      "`sandbox run post_bumps --set vehicle.mesh=builtin:sedan?vertices=900000`: a %zu-vertex sedan with "
      "%zu "
      "control points after knocking over a small tree and a shrub (rigid for the hull, denting the body by "
      "their contact impulses) and nudging a 0.2 m steel bollard at 15 km/h; coloured by permanent "
      "displacement (red %.3f m, blue none), residual crush %.3f m; the car went %.2f m into what it hit "
      "(the face contacts dent the surface between the control points).",
      car.dented.positions_m.size(), car.control_points, car.metrics.max_deviation_m,
      car.metrics.max_residual_crush_m, car.metrics.max_dynamic_crush_m);
  return {"minor_hits.png", caption};
}

}  // namespace sandbox::figures
