#include "dented_car.hpp"

#include <scenes/car_skin.hpp>
#include <scenes/scene_file.hpp>

#include <filesystem>

#include "render/heat_colours.hpp"
#include "render/renderer.hpp"
#include "render/vehicle_meshes.hpp"
#include "run_render.hpp"

namespace sandbox::figures {

DentedCar dentCar(scenes::SceneRun& run, std::optional<deform::SkinMethod> method) {
  const auto& sim = run.simulation();
  const vehicle::CarId id = run.carId(0);
  vehicle::DeformationSettings settings = sim.deformationSettings(id);
  if (method) settings.skin_method = *method;
  scenes::CarSkin skin(run.model(0).body, sim.controlRestPoints(id), settings);
  const std::vector<Eigen::Vector3d> displacements = sim.controlDisplacements(id);
  skin.update(displacements);
  DentedCar car;
  car.model = run.model(0);
  car.dented = skin.deformedMesh();
  // The wheels carried with the bodywork around them (as in the crash videos).
  std::vector<Eigen::Vector3f> hubs;
  for (const auto& w : car.model.wheels) hubs.push_back(w.centre_m.cast<float>());
  car.dented_wheels = car.model.wheels;
  if (!hubs.empty()) {
    const deform::Skin hub_skin =
        deform::Skin::build(hubs, sim.controlRestPoints(id),
                            deform::SkinOptions{settings.alpha, settings.k_nearest, 1, settings.skin_method});
    const auto shifts = embeddedShifts_m(hub_skin, hubs, displacements);
    for (std::size_t k = 0; k < shifts.size(); ++k) car.dented_wheels[k].centre_m += shifts[k];
  }
  car.colours = deform::displacementColours(skin.restPositions(), car.dented.positions_m);
  car.metrics = sim.metrics(id);
  car.control_points = sim.controlRestPoints(id).size();
  car.skin_method = settings.skin_method;
  return car;
}

DentedCar playAndDent(const std::string& scene, const std::vector<std::string>& overrides) {
  std::vector<scenes::Override> parsed;
  for (const auto& o : overrides) parsed.push_back(scenes::parseOverride(o));
  scenes::SceneRun run(scenes::loadScene(scene, parsed));
  run.runToEnd();
  return dentCar(run);
}

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

}  // namespace sandbox::figures
