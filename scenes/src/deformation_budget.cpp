// Levels of detail with their measured cost, and the deformation budget (deformation_budget.hpp).
#include <scenes/deformation_budget.hpp>

#include "scene_world.hpp"

#include <deform/skin.hpp>
#include <deform/solver_params.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace scenes {
namespace {

double cameraDistance(const SceneConfig& scene, std::size_t car) {
  const CameraConfig& camera = scene.camera;
  const Eigen::Vector3d& at = scene.vehicles[car].start.position_m;
  if (camera.mode == CameraMode::Chase) {
    const Eigen::Vector3d& followed =
        scene.vehicles[std::min(camera.follow, scene.vehicles.size() - 1)].start.position_m;
    return (at - followed).head<2>().norm();  // the chase camera rides with the car it follows
  }
  return (at - camera.eye_m).norm();
}

}  // namespace

const std::vector<DeformationLevel>& deformationLevels() {
  // deform's timing_ms over deform_steps.solved, this machine, one thread (docs/BENCHMARKS.md,
  // "Deformation levels", with the commands); against another car, over the steps the two cars touch
  // (car_to_car's whole run averaged the hit with the free spin after it, 4x less: `traffic`'s pile-up,
  // pressed together for 7 s, ran at 1.6x its budget). K changes the skin's cost, not the step's. A
  // coarser level than fast is not worth having: a car meeting an obstacle costs about what fast's does.
  // The last column is what a car against another cost before the two bodies were stepped as one
  // (deform::stepGroup); the group solve costs 3-5x less (0.103 / 0.213 / 0.707 / 1.49 / 3.03 ms, median
  // of three; docs/BENCHMARKS.md), but with those figures the planner gives traffic's three-car pile 250
  // points, where the bodies passed into each other and left -19 / -22 % of their energy unexplained
  // (docs/CRASH_CALIBRATION.md, "Two cars, one solve"). From 250 points a step in contact now takes substeps
  // of at most 0.5 ms (vehicle's contactSubstep_s), which closes that pile within 5.1 % at 120 Hz but costs
  // up to 4x the group solve's 4 x 2 below 500 Hz; the higher figures still bound that. A budget that
  // over-estimates chooses coarser levels, never a broken one. The obstacle column was measured at 500 Hz,
  // where the cap adds no substep; below, contactCostScale charges a level the substeps the cap adds.
  // fast's K is 8 since 2026-11-26: at K = 4 neither skin was right after the wall crash (idw left lobes
  // 9 cm deep across the crushed front, mls carried vertices 0.2 m past every control point), and K = 8
  // costs 8-16 % more to embed at 20,000 vertices (docs/TRADEOFF.md); the step's cost does not change.
  static const std::vector<DeformationLevel> levels = {
      {"fast", 60, 8, 2, 1, 0.013, 0.021, 0.34},    {"balanced", 60, 8, 4, 2, 0.044, 0.056, 0.69},
      {"accurate", 250, 8, 4, 2, 0.166, 0.18, 3.5}, {"fine", 500, 8, 4, 2, 0.31, 0.34, 8.4},
      {"finest", 1000, 8, 4, 2, 0.61, 0.66, 17.4},
  };
  return levels;
}

const DeformationLevel* deformationLevel(const std::string& name) {
  for (const DeformationLevel& level : deformationLevels())
    if (level.name == name) return &level;
  return nullptr;
}

void applyLevel(const DeformationLevel& level, vehicle::DeformationSettings& settings) {
  settings.control_points = level.control_points;
  settings.k_nearest = level.k_nearest;
  settings.substeps = level.substeps;
  settings.iterations = level.iterations;
}

double contactCostScale(const DeformationLevel& level, const vehicle::DeformationSettings& car,
                        double step_s) {
  vehicle::DeformationSettings settings = car;
  applyLevel(level, settings);
  const auto substeps = static_cast<uint32_t>(std::max(level.substeps, 1));
  if (!(step_s > 0)) return 1.0;
  // The substeps deform takes in contact (deform::substepsNoLongerThan, as DeformableBody::beginStep).
  const uint32_t taken = deform::substepsNoLongerThan(step_s, substeps, vehicle::contactSubstep_s(settings));
  return static_cast<double>(taken) / static_cast<double>(substeps);
}

BudgetPlan planDeformationBudget(const SceneConfig& scene, double budget_ms, int internal_steps,
                                 const std::vector<std::shared_ptr<const deform::VehicleModel>>* models) {
  const std::vector<DeformationLevel>& levels = deformationLevels();
  const std::size_t n = scene.vehicles.size();
  const double steps = std::max(internal_steps, 1);
  BudgetPlan plan;
  plan.budget_ms = budget_ms;
  plan.cars.resize(n);
  const std::vector<FirstContact> first =
      rehearseFirstContacts(scene, models ? *models : build::loadModels(scene), std::max(internal_steps, 1),
                            std::min(scene.duration_s, kRehearsal_s));
  for (std::size_t i = 0; i < n; ++i) {
    BudgetChoice& choice = plan.cars[i];
    choice.first_contact_s = first[i].time_s;
    choice.meets = first[i].meets;
    choice.camera_distance_m = cameraDistance(scene, i);
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const BudgetChoice &x = plan.cars[a], &y = plan.cars[b];
    if (x.first_contact_s != y.first_contact_s) return x.first_contact_s < y.first_contact_s;
    return x.camera_distance_m < y.camera_distance_m;
  });
  // The coarsest level (2 substeps x 1 iteration) is not offered to a car the script crashes into another:
  // two such bodies at 120 Hz do not hold apart (car_to_car's T-bone created 0.37 MJ; every car of traffic
  // at `fast`, 1.9 MJ; docs/CRASH_CALIBRATION.md, "Two cars, one solve"). Such a car starts one level up.
  std::vector<std::size_t> chosen(n, 0);  // index into levels
  for (std::size_t i = 0; i < n; ++i)
    if (plan.cars[i].meets == Meets::Car) chosen[i] = std::min<std::size_t>(1, levels.size() - 1);
  const double step_s = 1.0 / (scene.physics_hz * steps);  // one world step
  auto cost = [&](std::size_t car, std::size_t level) {
    const DeformationLevel& l = levels[level];
    const Meets meets = plan.cars[car].meets;
    if (meets == Meets::Obstacle)
      return l.obstacle_ms * contactCostScale(l, scene.vehicles[car].deformation.settings, step_s) * steps;
    return (meets == Meets::Car ? l.car_ms : l.driving_ms) * steps;
  };
  // A car whose scene names the spline skin stays at the levels that skin takes (its dense system and
  // per-frame node stage grow with N: deform::kSplineMostControlPoints).
  auto skinTakes = [&](std::size_t car, std::size_t level) {
    const DeformationConfig& d = scene.vehicles[car].deformation;
    return d.skin_method_auto || d.settings.skin_method != deform::SkinMethod::spline ||
           levels[level].control_points <= deform::kSplineMostControlPoints;
  };
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) total += cost(i, chosen[i]);
  plan.met = total <= budget_ms;
  // One level up at a time, in priority order, round after round, while the budget has room: the first
  // cars get the finer levels, and no car is left at the coarsest while another takes the finest.
  for (bool raised = plan.met; raised;) {
    raised = false;
    for (const std::size_t car : order) {
      const std::size_t next = chosen[car] + 1;
      if (next >= levels.size() || !skinTakes(car, next) ||
          total - cost(car, chosen[car]) + cost(car, next) > budget_ms)
        continue;
      total += cost(car, next) - cost(car, chosen[car]);
      chosen[car] = next;
      raised = true;
    }
  }
  for (std::size_t rank = 0; rank < n; ++rank) plan.cars[order[rank]].priority = rank;
  for (std::size_t i = 0; i < n; ++i) {
    plan.cars[i].level = levels[chosen[i]].name;
    plan.cars[i].estimated_ms = cost(i, chosen[i]);
  }
  plan.estimated_ms = total;
  return plan;
}

void applyBudget(const BudgetPlan& plan, SceneConfig& scene) {
  for (std::size_t i = 0; i < plan.cars.size() && i < scene.vehicles.size(); ++i) {
    const DeformationLevel* level = deformationLevel(plan.cars[i].level);
    if (!level) continue;
    applyLevel(*level, scene.vehicles[i].deformation.settings);
    scene.vehicles[i].deformation.preset = level->name;
    resolveSkinMethod(scene.vehicles[i].deformation);  // `auto` follows the level's control points
  }
}

}  // namespace scenes
