// Playing a scene: world and cars from the scene, drive scripts, metrics, timeline.
#include <scenes/car_skin.hpp>
#include <scenes/scene_run.hpp>
#include <scenes/surface_crush.hpp>
#include <vehicle/ccd_support.hpp>
#include "scene_world.hpp"

#include <deform/error.hpp>
#include <deform/mesh_import.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace scenes {
namespace {

using build::vehicleKey;
using build::withSource;

constexpr double kDegree = std::numbers::pi / 180.0;

// A body denser than any solid is a wrong mass or a mesh in the wrong units (millimetres read as metres):
// its points would be flung metres from a body centimetres wide (a drinks can of 1500 kg, 4e6 kg/m^3,
// spun its chassis without bound). Bounded from below by the bounding box, so no real vehicle is refused.
void refuseDenserThanAnySolid(const VehicleConfig& v, const deform::VehicleModel& model,
                              const std::string& where) {
  constexpr double kOsmium_kg_per_m3 = 22.59e3;  // the densest element
  const double box_m3 = deform::boundingBox(model.body).size_m().prod();
  if (!(box_m3 > 0) || v.mass_kg / box_m3 <= kOsmium_kg_per_m3) return;
  char figures[160];
  std::snprintf(figures, sizeof figures, " holds %.3g L: %g kg is denser than %.3g kg/m^3,", 1e3 * box_m3,
                v.mass_kg, v.mass_kg / box_m3);
  throw deform::InputError(
      where + ".mass_kg: the bounding box of " + v.mesh + figures +
      " more than any solid (osmium: 22,590 kg/m^3): check the mass, or the mesh's units "
      "(mesh_scale)");
}

}  // namespace

int defaultThreads() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::string hashHex(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

nlohmann::json profileJson(const std::vector<double>& profile_m) {
  nlohmann::json out = nlohmann::json::array();
  for (double c : profile_m) out.push_back(std::isnan(c) ? nlohmann::json(nullptr) : nlohmann::json(c));
  return out;
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error(path + ": cannot write");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot write (" + ec.message() + ")");
}

std::string timelineCsv(const std::vector<std::string>& columns,
                        const std::vector<std::vector<double>>& rows) {
  std::ostringstream out;
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << "\n";
  char number[32];
  for (const std::vector<double>& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      std::snprintf(number, sizeof number, "%.9g", row[i]);
      out << (i ? "," : "") << number;
    }
    out << "\n";
  }
  return out.str();
}

SceneRun::SceneRun(SceneConfig scene) : scene_(std::move(scene)) {
  const auto started = std::chrono::steady_clock::now();
  physics_substeps_ = static_cast<int>(std::ceil(kMinInternalRate_hz / scene_.physics_hz - 1e-9));
  physics_substeps_ = std::max(physics_substeps_, 1);
  const vehicle::WorldSettings world_settings = build::worldSettings(scene_, physics_substeps_);
  simulation_ =
      withSource(scene_.source, [&] { return std::make_unique<vehicle::Simulation>(world_settings); });
  total_steps_ = static_cast<uint64_t>(std::llround(scene_.duration_s * scene_.physics_hz));
  simulation_->setThreads(scene_.threads.value_or(defaultThreads()));
  const std::vector<std::shared_ptr<const deform::VehicleModel>> models = build::loadModels(scene_);
  for (std::size_t i = 0; i < scene_.vehicles.size(); ++i)
    refuseDenserThanAnySolid(scene_.vehicles[i], *models[i], scene_.source + ": " + vehicleKey(scene_, i));
  if (scene_.deformation_budget_ms) {
    budget_plan_ = planDeformationBudget(scene_, *scene_.deformation_budget_ms, physics_substeps_, &models);
    applyBudget(*budget_plan_, scene_);
  }
  for (std::size_t i = 0; i < scene_.vehicles.size(); ++i) {
    const VehicleConfig& v = scene_.vehicles[i];
    const std::string where = scene_.source + ": " + vehicleKey(scene_, i);
    const vehicle::VehicleSettings settings = build::carSettings(v, *models[i], where);
    const vehicle::CarId id = withSource(where + ".deformation", [&] {
      return simulation_->addDeformableCar(*models[i], settings, build::carStart(v), v.deformation.settings);
    });
    cars_.push_back(Car{id, models[i], DrivePlayer(v.drive), v.start.lateral_speed_kmh / 3.6, std::nullopt});
  }
  for (std::size_t i = 0; i < scene_.obstacles.size(); ++i) {
    const std::string where = scene_.source + ": obstacles[" + std::to_string(i) + "]";
    obstacle_ids_.push_back(withSource(
        where, [&] { return build::addObstacle(simulation_->world(), scene_.obstacles[i], where); }));
  }
  refuseStartingOverlaps();
  times_.setup_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
}

void SceneRun::refuseStartingOverlaps() const {
  // A car placed inside an obstacle or another car would start crushed (the sedan put in a wall ended 1 m
  // deformed on top of it). Touching is allowed: 1 cm.
  constexpr double kTouch_m = 0.01;
  const vehicle::World& world = simulation_->world();
  auto refuse = [&](const std::string& a, const std::string& b, double depth_m) {
    char by[64];
    std::snprintf(by, sizeof by, " by %.3f m", depth_m);
    throw deform::InputError(scene_.source + ": " + a + " overlaps " + b + " at the start" + by +
                             " (move one of them apart)");
  };
  for (std::size_t i = 0; i < cars_.size(); ++i) {
    const vehicle::ObstacleShape car = world.shapeOf({vehicle::EntityRef::Kind::Car, cars_[i].id});
    const std::string name = vehicleKey(scene_, i) + " (" + scene_.vehicles[i].name + ")";
    for (std::size_t j = 0; j < obstacle_ids_.size(); ++j) {
      const double depth_m =
          vehicle::overlapDepth_m(car, world.shapeOf({vehicle::EntityRef::Kind::Obstacle, obstacle_ids_[j]}));
      if (depth_m > kTouch_m) refuse(name, "obstacles[" + std::to_string(j) + "]", depth_m);
    }
    for (std::size_t k = i + 1; k < cars_.size(); ++k) {
      const double depth_m =
          vehicle::overlapDepth_m(car, world.shapeOf({vehicle::EntityRef::Kind::Car, cars_[k].id}));
      if (depth_m > kTouch_m)
        refuse(name, vehicleKey(scene_, k) + " (" + scene_.vehicles[k].name + ")", depth_m);
    }
  }
}

SceneRun::~SceneRun() = default;

double SceneRun::time_s() const {
  return simulation_->world().time_s();
}

uint64_t SceneRun::steps() const {
  return simulation_->world().stepCount() / static_cast<uint64_t>(physics_substeps_);
}

void SceneRun::step() {
  if (finished()) return;
  for (int k = 0; k < physics_substeps_; ++k) internalStep();
}

void SceneRun::internalStep() {
  vehicle::World& world = simulation_->world();
  const double dt = world.fixedDt_s();
  // The drive inputs count as tyres (they are what the wheels are told).
  const auto inputs_start = std::chrono::steady_clock::now();
  for (Car& car : cars_) {
    const vehicle::Car& chassis = world.car(car.id);
    build::driveCar(world, car.id,
                    car.override_input ? *car.override_input
                                       : car.driver.inputs(world.time_s(), chassis.forwardSpeed_mps(), dt),
                    car.lateral_speed_mps);
  }
  times_.tyres_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - inputs_start).count();
  simulation_->step();
  const vehicle::StepTimings timings = simulation_->lastTimings();
  times_.tyres_ms += timings.tyres_ms;
  times_.collide_ms += timings.collide_ms;
  times_.solve_ms += timings.solve_ms;
  times_.deform_ms += timings.deform_ms;
  times_.coupling_ms += timings.coupling_ms;
  times_.metrics_ms += timings.metrics_ms;
}

void SceneRun::overrideDriverInput(std::size_t car, std::optional<vehicle::DriverInput> input) {
  cars_.at(car).override_input = std::move(input);
}

void SceneRun::stepUntil(double t_s) {
  const double half_step = 0.5 / scene_.physics_hz;
  while (!finished() && time_s() < t_s - half_step) step();
}

void SceneRun::runToEnd() {
  while (!finished()) step();
}

int SceneRun::advance(double dt_s) {
  if (!(dt_s > 0) || !std::isfinite(dt_s)) {
    throw deform::InputError("dt_s: a frame must be finite and > 0 s (got " + std::to_string(dt_s) + ")");
  }
  frame_time_s_ += dt_s;
  // Whole steps the frames add up to; the tolerance absorbs the rounding of summed frame times.
  const auto due = static_cast<uint64_t>(std::floor(frame_time_s_ * scene_.physics_hz + 1e-6));
  int taken = 0;
  while (!finished() && steps() < due) {
    step();
    ++taken;
  }
  return taken;
}

bool SceneRun::diverged() const {
  for (const Car& car : cars_) {
    if (simulation_->metrics(car.id).diverged) return true;
  }
  return false;
}

std::string SceneRun::divergence() const {
  std::size_t first = cars_.size();
  for (std::size_t i = 0; i < cars_.size(); ++i) {
    const vehicle::CrashMetrics m = simulation_->metrics(cars_[i].id);
    if (m.diverged &&
        (first == cars_.size() || m.diverged_at_s < simulation_->metrics(cars_[first].id).diverged_at_s))
      first = i;
  }
  if (first == cars_.size()) return "";
  const vehicle::CrashMetrics m = simulation_->metrics(cars_[first].id);
  char when[64];
  std::snprintf(when, sizeof when, " at t = %.4f s", m.diverged_at_s);
  return scene_.vehicles[first].name + ": " + m.diverged_what + when;
}

namespace {

nlohmann::json metricsJson(const vehicle::CrashMetrics& m) {
  nlohmann::json j;
  j["impact_speed_mps"] = m.impact_speed_mps;
  j["rebound_speed_mps"] = m.rebound_speed_mps;
  j["restitution"] = m.restitution;
  j["residual_crush_m"] = m.residual_crush_m;
  j["max_residual_crush_m"] = m.max_residual_crush_m;
  j["crush_profile_m"] = profileJson(m.crush_profile_m);
  j["crush_height_m"] = m.crush_height_m;
  j["max_dynamic_crush_m"] = m.max_dynamic_crush_m;
  j["crushed_volume_m3"] = m.crushed_volume_m3;
  // dissipated_J holds other_work_J (tyres, engine, drag, gravity, rigid contacts): negative when the
  // engine put more in than those took out. The parts are listed so that the balance can be read.
  j["energy"] = {
      {"kinetic_initial_J", m.energy.kinetic_initial_J}, {"plastic_work_J", m.energy.plastic_work_J},
      {"damping_loss_J", m.energy.damping_loss_J},       {"contact_work_J", m.energy.contact_work_J},
      {"inertial_work_J", m.energy.inertial_work_J},     {"obstacle_work_J", m.energy.obstacle_work_J},
      {"dissipated_J", m.energy.dissipated_J},           {"kinetic_final_J", m.energy.kinetic_final_J},
      {"crush_work_J", m.energy.crush_work_J},           {"other_work_J", m.energy.other_work_J},
      {"body_energy_J", m.energy.body_energy_J},         {"balance_error_J", m.energy.balance_error_J},
      {"contact_loss_J", m.energy.contact_loss_J},       {"elastic_energy_J", m.energy.elastic_energy_J}};
  j["max_deviation_m"] = m.max_deviation_m;
  j["max_penetration_m"] = m.max_penetration_m;
  j["tunnelled"] = m.tunnelled;
  j["diverged"] = m.diverged;
  if (m.diverged) j["diverged_at"] = {{"time_s", m.diverged_at_s}, {"what", m.diverged_what}};
  j["impacted"] = m.impacted;
  return j;
}

}  // namespace

vehicle::CrushStations SceneRun::surfaceCrush(std::size_t car, SkinCache& skins) const {
  const vehicle::CarId id = cars_[car].id;
  const vehicle::CrashMetrics m = simulation_->metrics(id);
  if (!m.impacted) return {};
  const deform::Mesh& body = cars_[car].model->body;
  const auto skin = skins.get(body, simulation_->controlRestPoints(id), simulation_->deformationSettings(id));
  const std::vector<Eigen::Vector3d> displacements = simulation_->controlDisplacements(id);
  std::vector<Eigen::Vector3f> now(body.positions_m.size());
  skin->deform(body.positions_m.data(), displacements.data(), now.data(), 0);
  return scenes::surfaceCrush(body, now, m.impact_direction_vehicle);
}

nlohmann::json SceneRun::summary() const {
  nlohmann::json out;
  out["scene"] = scene_.name;
  out["source"] = scene_.source;
  bool any_diverged = false;
  nlohmann::json cars = nlohmann::json::array();
  SkinCache skins;  // one skin per body mesh, control mesh and skin settings
  for (std::size_t i = 0; i < cars_.size(); ++i) {
    const vehicle::CrashMetrics m = simulation_->metrics(cars_[i].id);
    any_diverged = any_diverged || m.diverged;
    nlohmann::json car = metricsJson(m);
    // The same crush measured on the car's own surface: the render mesh as the car's skin moves it.
    const vehicle::CrushStations surface = surfaceCrush(i, skins);
    car["surface_residual_crush_m"] = surface.mean_m;
    car["surface_max_residual_crush_m"] = surface.max_m;
    car["surface_crush_profile_m"] = profileJson(surface.profile_m);
    car["surface_crush_height_m"] = surface.height_m;
    const vehicle::Simulation::Refinement refinement = simulation_->refinement(cars_[i].id);
    car["control_points"] = refinement.control_points;
    car["refinements"] = refinement.refinements;
    car["refinement_bounded"] = refinement.bounded;
    car["name"] = scene_.vehicles[i].name;
    const vehicle::Car& chassis = simulation_->world().car(cars_[i].id);
    const Eigen::Vector3d p = chassis.vehiclePose().position_m;
    car["final_position_m"] = {p.x(), p.y(), p.z()};
    car["final_speed_mps"] = chassis.velocity_mps().norm();
    if (i == 0) {
      for (auto it = car.begin(); it != car.end(); ++it) out[it.key()] = it.value();
    }
    cars.push_back(car);
  }
  out["diverged"] = any_diverged;
  out["cars"] = cars;
  const vehicle::Simulation::EnergyWatchReport watch = simulation_->energyWatch();
  out["energy_watch"] = {{"largest_created_J", watch.largest_created_J},
                         {"largest_created_share", watch.largest_created_share},
                         {"through_J", watch.through_J},
                         {"drive_work_J", watch.drive_work_J},
                         {"tolerance_share", vehicle::kEnergyWatchTolerance}};
  // Per car: body steps that ran the solver and those skipped asleep. Like timing_ms, not state: a
  // resumed run counts only its own steps.
  nlohmann::json deform_steps = nlohmann::json::array();
  for (const Car& car : cars_) {
    const vehicle::Simulation::DeformCounts counts = simulation_->deformCounts(car.id);
    deform_steps.push_back({{"solved", counts.steps}, {"skipped", counts.skipped}});
  }
  out["deform_steps"] = deform_steps;
  out["state_hash"] = hashHex(stateHash());
  out["steps"] = steps();
  out["time_s"] = time_s();
  out["physics_hz"] = scene_.physics_hz;
  out["physics_substeps"] = physics_substeps_;
  out["threads"] = simulation_->threads();
  if (budget_plan_) {
    nlohmann::json cars_budget = nlohmann::json::array();
    for (std::size_t i = 0; i < budget_plan_->cars.size(); ++i) {
      const BudgetChoice& c = budget_plan_->cars[i];
      const vehicle::DeformationSettings& d = scene_.vehicles[i].deformation.settings;
      cars_budget.push_back(
          {{"name", scene_.vehicles[i].name},
           {"level", c.level},
           {"control_points", d.control_points},
           {"k_nearest", d.k_nearest},
           {"substeps", d.substeps},
           {"iterations", d.iterations},
           {"estimated_ms", c.estimated_ms},
           {"meets", c.meets == Meets::Car        ? "car"
                     : c.meets == Meets::Obstacle ? "obstacle"
                                                  : "nothing"},
           {"priority", c.priority},
           {"first_contact_s",
            std::isfinite(c.first_contact_s) ? nlohmann::json(c.first_contact_s) : nlohmann::json()},
           {"camera_distance_m", c.camera_distance_m}});
    }
    // What the bodies' steps took per physics step in this run, all cars together (asleep ones cost
    // next to nothing, so this is at most the estimate's every-body-awake figure plus the machine's noise).
    const uint64_t own_steps = steps() - steps_at_start_;  // like timing_ms, this run's own
    const double measured = own_steps > 0 ? times_.deform_ms / static_cast<double>(own_steps) : 0.0;
    out["deformation_budget"] = {{"budget_ms", budget_plan_->budget_ms},
                                 {"estimated_ms", budget_plan_->estimated_ms},
                                 {"met", budget_plan_->met},
                                 {"measured_ms_per_step", measured},
                                 {"cars", cars_budget}};
  }
  // Every stage, and physics (tyres + collide + solve) as a subtotal for older readers.
  out["timing_ms"] = {
      {"setup", times_.setup_ms},     {"tyres", times_.tyres_ms},       {"collide", times_.collide_ms},
      {"solve", times_.solve_ms},     {"deform", times_.deform_ms},     {"coupling", times_.coupling_ms},
      {"metrics", times_.metrics_ms}, {"embed", times_.embed_ms},       {"render", times_.render_ms},
      {"output", times_.output_ms},   {"physics", times_.physics_ms()}, {"total", times_.total_ms}};
  return out;
}

std::vector<std::string> SceneRun::timelineColumns() const {
  std::vector<std::string> columns = {"time_s", "step"};
  for (const VehicleConfig& v : scene_.vehicles) {
    for (const char* c :
         {"x_m", "y_m", "z_m", "speed_kmh", "heading_deg", "tilt_deg", "throttle", "brake", "steering",
          "max_deviation_m", "max_dynamic_crush_m", "residual_crush_m", "plastic_work_J"}) {
      columns.push_back(v.name + "." + c);
    }
  }
  return columns;
}

std::vector<double> SceneRun::timelineValues() const {
  std::vector<double> values = {time_s(), static_cast<double>(steps())};
  for (const Car& car : cars_) {
    const vehicle::Car& chassis = simulation_->world().car(car.id);
    const vehicle::Pose pose = chassis.vehiclePose();
    const Eigen::Vector3d forward = pose.orientation * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d up = pose.orientation * Eigen::Vector3d::UnitZ();
    const vehicle::CrashMetrics m = simulation_->metrics(car.id);
    const vehicle::DriverInput& input = chassis.input();
    values.insert(
        values.end(),
        {pose.position_m.x(), pose.position_m.y(), pose.position_m.z(), chassis.velocity_mps().norm() * 3.6,
         std::atan2(forward.y(), forward.x()) / kDegree, std::acos(std::clamp(up.z(), -1.0, 1.0)) / kDegree,
         input.throttle, input.brake, input.steering, m.max_deviation_m, m.max_dynamic_crush_m,
         m.residual_crush_m, m.energy.plastic_work_J});
  }
  return values;
}

}  // namespace scenes
