// Drawing a scene run: cars (skinned body, wheels on their hubs), obstacles, camera, heat map.
#include "run_render.hpp"

#include "elapsed.hpp"

#include <deform/control_mesh.hpp>

#include <vehicle/obstacle_shape.hpp>

#include <chrono>
#include <cmath>
#include <exception>
#include <memory>

#include "render/heat_colours.hpp"
#include "render/vehicle_meshes.hpp"

namespace sandbox {
namespace {

Eigen::Matrix4f matrixOf(const vehicle::Pose& pose) {
  return pose.isometry().matrix().cast<float>();
}

// A convex point set as flat-shaded triangles (each triangle its own corners and face normal).
deform::Mesh flatHull(const std::vector<Eigen::Vector3d>& points) {
  const deform::ControlMesh hull = deform::convexHull(points, "obstacle", deform::FacetSplit::Diagonals);
  deform::Mesh mesh;
  for (const auto& t : hull.triangles) {
    const Eigen::Vector3d a = hull.points_m[t[0]], b = hull.points_m[t[1]], c = hull.points_m[t[2]];
    const Eigen::Vector3f n = (b - a).cross(c - a).normalized().cast<float>();
    const auto base = static_cast<uint32_t>(mesh.positions_m.size());
    for (const Eigen::Vector3d& p : {a, b, c}) {
      mesh.positions_m.push_back(p.cast<float>());
      mesh.normals.push_back(n);
    }
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  return mesh;
}

// The obstacle's surface in its own frame (where obstaclePose places it); empty for the ground.
deform::Mesh obstacleLocalMesh(const vehicle::World& world, vehicle::ObstacleId id) {
  const vehicle::ObstacleShape shape =
      vehicle::transformShape(world.obstacleShape(id), world.obstaclePose(id));
  switch (shape.type) {
    case vehicle::ShapeType::Box: {
      std::vector<Eigen::Vector3d> corners;
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d sign((c & 1) ? 1 : -1, (c & 2) ? 1 : -1, (c & 4) ? 1 : -1);
        corners.push_back(shape.centre_m + shape.axes * sign.cwiseProduct(shape.half_extents_m));
      }
      return flatHull(corners);
    }
    case vehicle::ShapeType::Convex:
      return flatHull(shape.vertices_m);
    case vehicle::ShapeType::Cylinder:
    case vehicle::ShapeType::Capsule: {
      const Eigen::Vector3d axis = shape.b_m - shape.a_m;
      const double length = axis.norm();
      deform::Mesh mesh = deform::makeWheelMesh(shape.radius_m, length, 24);  // around Y
      const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), axis);
      const Eigen::Vector3d middle = 0.5 * (shape.a_m + shape.b_m);
      for (Eigen::Vector3f& p : mesh.positions_m) p = (turn * p.cast<double>() + middle).cast<float>();
      mesh.normals.clear();
      deform::computeVertexNormals(mesh);
      return mesh;
    }
    default:
      return {};
  }
}

}  // namespace

render::Camera sceneCamera(const scenes::SceneRun& run) {
  const scenes::CameraConfig& c = run.scene().camera;
  const vehicle::Car& car = run.simulation().world().car(run.carId(c.follow));
  render::Camera camera;
  switch (c.mode) {
    case scenes::CameraMode::Chase:
      camera = render::chaseCamera(car.vehiclePose().isometry(), c.distance_m, c.height_m);
      break;
    case scenes::CameraMode::Side:
      camera = render::sideCamera(c.eye_m, car.bodyPose().position_m);
      break;
    case scenes::CameraMode::Fixed:
      camera = render::sideCamera(c.eye_m, c.target_m);
      break;
  }
  camera.fov_y_deg = static_cast<float>(c.fov_deg);
  const float distance = (camera.target_m - camera.eye_m).norm();
  camera.near_m = std::max(1e-3f, std::min(0.1f, distance * 0.05f));
  return camera;
}

render::Environment sceneEnvironment(const scenes::SceneRun& run) {
  const deform::Aabb box = render::vehicleBounds(run.model(0));
  const double diagonal = box.diagonal_m();
  render::Environment environment;
  environment.ground.visible = run.scene().ground;
  environment.ground.height_m = 0.0f;
  environment.ground.centre_m = run.scene().vehicles[0].start.position_m.head<2>().cast<float>();
  environment.ground.radius_m = static_cast<float>(std::max(diagonal, 1e-3) * 30.0);
  environment.ground.grid_spacing_m = render::gridSpacingFor(diagonal);
  return environment;
}

RunRenderer::RunRenderer(const scenes::SceneRun& run, const scenes::OutputConfig& outputs,
                         scenes::StageTimes& times)
    : heatmap_(outputs.heatmap),
      aspect_(static_cast<float>(outputs.width) / static_cast<float>(std::max(outputs.height, 1))) {
  auto start = Clock::now();
  const vehicle::Simulation& simulation = run.simulation();
  // Cars of one build (the same loaded model and shared control mesh) with the same skin settings share
  // one set of weights, rest copy, triangles and grid (DESIGN.md section 8).
  scenes::CarSkinBuilds builds;
  for (std::size_t i = 0; i < run.carCount(); ++i) {
    CarMeshes car;
    const vehicle::CarId id = run.carId(i);
    const vehicle::DeformationSettings& settings = simulation.deformationSettings(id);
    car.skin = std::make_unique<scenes::CarSkin>(
        builds.get(run.model(i).body, simulation.controlRestPoints(id), settings));
    for (const vehicle::WheelSettings& w : simulation.world().car(id).wheelSettings())
      car.hub_rest_m.push_back(w.centre_m.cast<float>());
    if (!car.hub_rest_m.empty()) {
      const vehicle::DeformationSettings& d = simulation.deformationSettings(id);
      car.hub_skin = deform::Skin::build(car.hub_rest_m, simulation.controlRestPoints(id),
                                         deform::SkinOptions{d.alpha, d.k_nearest, 1, d.skin_method});
    }
    const double diagonal = deform::boundingBox(run.model(i).body).diagonal_m();
    car.full_scale_m =
        static_cast<float>(outputs.heatmap_full_scale_m > 0 ? outputs.heatmap_full_scale_m : 0.06 * diagonal);
    cars_.push_back(std::move(car));
  }
  times.embed_ms += msSince(start);

  start = Clock::now();
  render::RenderSettings settings{outputs.width, outputs.height, outputs.samples};
  // A scene's frames are a video, drawn for speed: its anti-aliasing (outputs.samples > 1) is edge
  // smoothing after the readback rather than llvmpipe's costly 4x MSAA, and its shadow map is 1024 texels
  // wide, which the soft penumbra hides (docs/BENCHMARKS.md compares the frames with the old ones).
  settings.smooth_edges = outputs.samples > 1;
  settings.shadow_map_size = 1024;
  renderer_ = std::make_unique<render::Renderer>(settings);
  for (std::size_t i = 0; i < run.carCount(); ++i) {
    std::vector<render::MeshData> meshes =
        render::vehicleMeshes(run.model(i), run.scene().vehicles[i].colour);
    cars_[i].body = renderer_->addMesh(meshes[0]);
    if (heatmap_)
      renderer_->setColours(
          cars_[i].body, std::vector<Eigen::Vector3f>(meshes[0].positions_m.size(), deform::heatColour(0)));
    for (std::size_t w = 1; w < meshes.size(); ++w) cars_[i].wheels.push_back(renderer_->addMesh(meshes[w]));
  }
  const vehicle::World& world = simulation.world();
  for (std::size_t i = 0; i < run.scene().obstacles.size(); ++i) {
    const vehicle::ObstacleId id = run.obstacleId(i);
    const deform::Mesh local = obstacleLocalMesh(world, id);
    if (local.triangles.empty()) continue;
    render::MeshData data = render::meshData(local, run.scene().obstacles[i].colour);
    data.specular = 0.1f;
    data.shininess = 20.0f;
    obstacles_.push_back({renderer_->addMesh(data), id});
  }
  environment_ = sceneEnvironment(run);
  times.render_ms += msSince(start);
}

RunRenderer::~RunRenderer() = default;

render::Image RunRenderer::frame(const scenes::SceneRun& run, scenes::StageTimes& times) {
  draw(run, times);
  const auto start = Clock::now();
  render::Image image = readback();
  finishFrame(image);
  times.render_ms += msSince(start);
  return image;
}

render::Image RunRenderer::readback() {
  return renderer_->readPixels();
}

void RunRenderer::finishFrame(render::Image& image) const {
  renderer_->finishImage(image);
}

void RunRenderer::rebind(const scenes::SceneRun& run, std::size_t i) {
  // The car's body was refined (vehicle::DeformationSettings::refine): its render mesh and wheel hubs
  // follow the finer control points, with weights of their own.
  const vehicle::Simulation& simulation = run.simulation();
  const vehicle::CarId id = run.carId(i);
  const vehicle::DeformationSettings& d = simulation.deformationSettings(id);
  CarMeshes& car = cars_[i];
  car.skin = std::make_unique<scenes::CarSkin>(run.model(i).body, simulation.controlRestPoints(id), d);
  if (!car.hub_rest_m.empty())
    car.hub_skin = deform::Skin::build(car.hub_rest_m, simulation.controlRestPoints(id),
                                       deform::SkinOptions{d.alpha, d.k_nearest, 1, d.skin_method});
}

void RunRenderer::draw(const scenes::SceneRun& run, scenes::StageTimes& times) {
  const vehicle::Simulation& simulation = run.simulation();
  const vehicle::World& world = simulation.world();
  auto start = Clock::now();
  const render::Camera camera = sceneCamera(run);
  std::vector<uint8_t> changed(cars_.size(), 0);
  std::vector<std::vector<Eigen::Vector3d>> displacements_of(cars_.size());
  std::vector<std::size_t> in_view;
  for (std::size_t i = 0; i < cars_.size(); ++i) {
    displacements_of[i] = simulation.controlDisplacements(run.carId(i));
    const std::vector<Eigen::Vector3d>& displacements = displacements_of[i];
    if (displacements.size() != cars_[i].skin->skin().controlPointCount()) rebind(run, i);
    scenes::CarSkin& skin = *cars_[i].skin;
    // A car out of the camera's view is not embedded this frame (DESIGN.md section 8): its skin catches
    // up, exactly, on the frame it comes into view (it recomputes what moved since its last update).
    const deform::Aabb rest = skin.restBounds();
    const vehicle::Pose pose = world.car(run.carId(i)).vehiclePose();
    const Eigen::Vector3d centre_m = pose.toWorld(0.5 * (rest.min_m + rest.max_m));
    // Grown by a diagonal for its shadow, which may fall into view from outside it.
    const double radius_m = 1.5 * rest.diagonal_m() + skin.displacementBound_m(displacements);
    if (!render::sphereInView(camera, aspect_, centre_m.cast<float>(), static_cast<float>(radius_m))) {
      ++embeds_out_of_view_;
      continue;
    }
    in_view.push_back(i);
  }
  // Each car's embedding touches only its own skin: the cars in view in parallel, on the run's threads
  // (Simulation::threads, `run --threads`); the picture does not depend on their number.
  const auto count = static_cast<std::ptrdiff_t>(in_view.size());
  const int threads = simulation.threads();
  std::vector<std::exception_ptr> errors(in_view.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && count > 1)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const std::size_t i = in_view[static_cast<std::size_t>(k)];
    try {
      CarMeshes& car = cars_[i];
      const std::vector<Eigen::Vector3d>& displacements = displacements_of[i];
      car.obstacles_near.gather(simulation, run.carId(i), car.skin->restBounds(),
                                car.skin->displacementBound_m(displacements));
      changed[i] = car.skin->update(displacements, car.obstacles_near.shapes()) > 0 ? 1 : 0;
    } catch (...) {
      errors[static_cast<std::size_t>(k)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  times.embed_ms += msSince(start);

  start = Clock::now();
  for (std::size_t i = 0; i < cars_.size(); ++i) {
    CarMeshes& car = cars_[i];
    const vehicle::Car& chassis = world.car(run.carId(i));
    if (changed[i]) {
      renderer_->updatePositions(car.body, car.skin->positions(), car.skin->normals());
      if (heatmap_) {
        renderer_->setColours(car.body, deform::displacementColours(car.skin->restPositions(),
                                                                    car.skin->positions(), car.full_scale_m));
      }
    }
    const vehicle::Pose vehicle_pose = chassis.vehiclePose();
    renderer_->setTransform(car.body, matrixOf(vehicle_pose));
    // Hubs moved with the bodywork around them, in the ground plane of the car (the suspension keeps
    // their height).
    const std::vector<Eigen::Vector3d> shifts =
        car.hub_rest_m.empty() ? std::vector<Eigen::Vector3d>{}
                               : embeddedShifts_m(car.hub_skin, car.hub_rest_m, displacements_of[i]);
    for (std::size_t w = 0; w < car.wheels.size() && w < chassis.wheels().size(); ++w) {
      vehicle::Pose wheel = chassis.wheelPose(w);
      if (w < shifts.size()) wheel.position_m += vehicle_pose.orientation * shifts[w];
      renderer_->setTransform(car.wheels[w], matrixOf(wheel));
    }
  }
  for (const ObstacleMesh& o : obstacles_)
    renderer_->setTransform(o.mesh, matrixOf(world.obstaclePose(o.id)));
  renderer_->render(camera, environment_);
  times.render_ms += msSince(start);
}

std::vector<Eigen::Vector3d> embeddedShifts_m(const deform::Skin& skin,
                                              const std::vector<Eigen::Vector3f>& points_m,
                                              const std::vector<Eigen::Vector3d>& displacements_m) {
  std::vector<Eigen::Vector3f> moved(points_m.size());
  skin.deform(points_m.data(), displacements_m.data(), moved.data(), 1);
  std::vector<Eigen::Vector3d> shifts;
  for (std::size_t k = 0; k < points_m.size(); ++k) {
    Eigen::Vector3d shift = (moved[k] - points_m[k]).cast<double>();
    shift.z() = 0;  // the suspension keeps the hub's height
    shifts.push_back(shift);
  }
  return shifts;
}

deform::Mesh deformedBody(const scenes::SceneRun& run, std::size_t car) {
  const vehicle::Simulation& simulation = run.simulation();
  const vehicle::CarId id = run.carId(car);
  scenes::CarSkin skin(run.model(car).body, simulation.controlRestPoints(id),
                       simulation.deformationSettings(id));
  const std::vector<Eigen::Vector3d> displacements = simulation.controlDisplacements(id);
  scenes::SkinObstacles obstacles;
  obstacles.gather(simulation, id, skin.restBounds(), skin.displacementBound_m(displacements));
  skin.update(displacements, obstacles.shapes());
  return skin.deformedMesh();
}

}  // namespace sandbox
