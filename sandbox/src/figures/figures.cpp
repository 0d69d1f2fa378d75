#include "figures.hpp"

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/skin.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "dented_car.hpp"
#include "flat_mesh.hpp"
#include "image_tiles.hpp"
#include "render/heat_colours.hpp"
#include "render/renderer.hpp"
#include "render/vehicle_meshes.hpp"

namespace sandbox::figures {
namespace {

const Eigen::Vector3f kBodyRed{0.75f, 0.08f, 0.06f};
const Eigen::Vector3f kHullBlue{0.30f, 0.45f, 0.70f};

std::vector<Eigen::Vector3d> toDouble(const std::vector<Eigen::Vector3f>& points) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(p.cast<double>());
  return out;
}

render::RenderSettings panelSettings(const FigureOptions& o) {
  render::RenderSettings s;
  s.width = o.panel_width;
  s.height = o.panel_height;
  s.samples = o.samples;
  return s;
}

/// Renders each of `meshes` alone (the others hidden) from the same camera.
std::vector<render::Image> renderEachAlone(render::Renderer& renderer,
                                           const std::vector<render::Renderer::MeshId>& ids,
                                           const std::vector<std::vector<render::Renderer::MeshId>>& panels,
                                           const render::Camera& camera,
                                           const render::Environment& environment) {
  std::vector<render::Image> images;
  for (const auto& shown : panels) {
    for (auto id : ids) renderer.setVisible(id, std::find(shown.begin(), shown.end(), id) != shown.end());
    images.push_back(renderer.renderImage(camera, environment));
  }
  return images;
}

}  // namespace

Figure convexHullFigure(const FigureOptions& o) {
  const deform::VehicleModel car = deform::makeSedan(20000);
  const auto points = toDouble(car.body.positions_m);
  render::Renderer renderer(panelSettings(o));
  std::vector<render::Renderer::MeshId> ids;
  const auto body = renderer.addMesh(render::meshData(car.body, kBodyRed));
  ids.push_back(body);
  std::vector<render::Renderer::MeshId> wheels;
  for (const auto& w : car.wheels) {
    render::MeshData wheel =
        render::meshData(deform::makeWheelMesh(w.radius_m, w.width_m), {0.08f, 0.08f, 0.08f});
    wheel.model.block<3, 1>(0, 3) = w.centre_m.cast<float>();
    wheels.push_back(renderer.addMesh(wheel));
  }
  ids.insert(ids.end(), wheels.begin(), wheels.end());
  const deform::ControlMesh hull = deform::convexHull(points, "builtin:sedan");
  const auto hull_id = renderer.addMesh(render::meshData(facetedMesh(hull), kHullBlue));
  ids.push_back(hull_id);
  std::vector<std::vector<render::Renderer::MeshId>> panels;
  std::vector<render::Renderer::MeshId> with_wheels = wheels;
  with_wheels.push_back(body);
  panels.push_back(with_wheels);
  panels.push_back({hull_id});
  char caption[1024];
  int used =
      std::snprintf(caption, sizeof caption,
                    "(a) builtin:sedan, %zu vertices; (b) its convex hull, %zu vertices (qhull); (c) control "
                    "meshes with",
                    car.body.positions_m.size(), hull.hull_vertex_count);
  for (std::size_t n : {1000u, 250u, 60u, 16u}) {
    const deform::ControlMesh control = deform::buildControlMesh(points, n, "builtin:sedan");
    const auto stats = deform::controlMeshStats(control);
    const auto id = renderer.addMesh(render::meshData(facetedMesh(control), kHullBlue));
    ids.push_back(id);
    panels.push_back({id});
    used += std::snprintf(caption + used, sizeof caption - static_cast<std::size_t>(used),
                          " %zu (largest gap %.2f m)%s", control.points_m.size(), stats.largest_gap_m,
                          n == 16 ? "" : ",");
  }
  std::snprintf(caption + used, sizeof caption - static_cast<std::size_t>(used),
                " control points: the level of detail, reduced automatically from the hull.");
  deform::Aabb box = deform::boundingBox(car.body);
  box.min_m.z() = 0;  // the wheels stand on the ground
  const render::Camera camera = render::presetCamera("quarter", box, renderer.aspect());
  const render::Environment environment = render::environmentAround(box);
  save(o, "convex_hull.png", tileImages(renderEachAlone(renderer, ids, panels, camera, environment), 3));
  return {"convex_hull.png", caption};
}

Figure weightingFigure(const FigureOptions& o) {
  // A plate held by its eight corners; the front-left top corner is lifted by lift_m.
  const deform::Mesh plate = deform::makeBox({2.0, 2.0, 0.1}, 40000);
  const auto control = deform::buildControlMesh(toDouble(plate.positions_m), 8, "plate");
  uint32_t corner = 0;
  for (uint32_t i = 0; i < control.points_m.size(); ++i)
    if (control.points_m[i].sum() > control.points_m[corner].sum()) corner = i;
  const double lift_m = 0.6;
  std::vector<Eigen::Vector3d> displacement(control.points_m.size(), Eigen::Vector3d::Zero());
  displacement[corner] = {0, 0, lift_m};

  render::Renderer renderer(panelSettings(o));
  render::MeshData data = render::meshData(plate, kHullBlue);
  data.model.block<3, 1>(0, 3) = Eigen::Vector3f(0, 0, 0.3f);
  const auto id = renderer.addMesh(data);
  deform::Aabb box = deform::boundingBox(plate);
  box.max_m.z() += lift_m + 0.3;
  box.min_m.z() = 0;
  const render::Camera camera = render::presetCamera("quarter", box, renderer.aspect());
  const render::Environment environment = render::environmentAround(box);

  std::vector<render::Image> panels;
  char caption[1024];
  int used =
      std::snprintf(caption, sizeof caption,
                    "A %zu-vertex plate embedded in its 8 corner control points (dense weights); one corner "
                    "lifted by %.1f m. Share of the plate moving more than 10 %% of the lift:",
                    plate.positions_m.size(), lift_m);
  for (double alpha : {1.0, 2.0, 3.0, 4.0, 5.0}) {
    const auto skin = deform::Skin::build(plate.positions_m, control.points_m, {alpha, 0, 0});
    std::vector<Eigen::Vector3f> moved(plate.positions_m.size());
    skin.deform(plate.positions_m.data(), displacement.data(), moved.data());
    std::size_t affected = 0;
    for (std::size_t j = 0; j < moved.size(); ++j)
      affected += (moved[j] - plate.positions_m[j]).norm() > 0.1 * lift_m;
    deform::Mesh bent = plate;
    bent.positions_m = moved;
    deform::computeVertexNormals(bent);
    renderer.updatePositions(id, bent.positions_m, bent.normals);
    renderer.setColours(id,
                        deform::displacementColours(plate.positions_m, moved, static_cast<float>(lift_m)));
    panels.push_back(renderer.renderImage(camera, environment));
    used += std::snprintf(caption + used, sizeof caption - static_cast<std::size_t>(used),
                          " alpha = %.0f: %.0f %%%s", alpha, 100.0 * double(affected) / double(moved.size()),
                          alpha < 5 ? ";" : ".");
  }
  save(o, "control_point_weighting.png", tileImages(panels, 5));
  return {"control_point_weighting.png", caption};
}

Figure canFigure(const FigureOptions& o) {
  const deform::Mesh can = deform::makeCan(20000);
  const auto points = toDouble(can.positions_m);
  const auto control = deform::buildControlMesh(points, 60, "builtin:can");
  const auto skin = deform::Skin::build(can.positions_m, control.points_m, {3.5, 8, 0});
  uint32_t top = 0;  // a control point on the rim
  for (uint32_t i = 0; i < control.points_m.size(); ++i)
    if (control.points_m[i].z() + control.points_m[i].x() >
        control.points_m[top].z() + control.points_m[top].x())
      top = i;

  render::Renderer renderer(panelSettings(o));
  const auto body = renderer.addMesh(render::meshData(can, {0.80f, 0.06f, 0.08f}));
  const auto cage = renderer.addMesh(render::meshData(facetedMesh(control), kHullBlue));
  const deform::Aabb box = deform::boundingBox(can);
  const render::Camera camera = render::presetCamera("quarter", box, renderer.aspect());
  const render::Environment environment = render::environmentAround(box);
  std::vector<render::Image> panels =
      renderEachAlone(renderer, {body, cage}, {{body}, {cage}}, camera, environment);
  renderer.setVisible(body, true);
  renderer.setVisible(cage, false);
  std::vector<float> weight(can.positions_m.size());
  float largest = 0;
  for (std::size_t j = 0; j < weight.size(); ++j)
    largest = std::max(largest, weight[j] = skin.weight(j, top));
  std::vector<Eigen::Vector3f> colours(weight.size());
  for (std::size_t j = 0; j < weight.size(); ++j) colours[j] = deform::heatColour(weight[j] / largest);
  renderer.setColours(body, colours);
  panels.push_back(renderer.renderImage(camera, environment));
  save(o, "drinks_can.png", tileImages(panels, 3));
  char caption[512];
  std::snprintf(caption, sizeof caption,
                "builtin:can (%zu vertices, 330 ml), its 60-point control mesh, and the influence of one rim "
                "control point (K = 8, alpha = 3.5; red = its largest weight, %.2f).",
                can.positions_m.size(), static_cast<double>(largest));
  return {"drinks_can.png", caption};
}

}  // namespace sandbox::figures
