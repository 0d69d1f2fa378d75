// Levels of detail with their measured cost, and the deformation budget (deformation_budget.hpp).
#include <scenes/deformation_budget.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace scenes {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
constexpr double kCarReach_m = 2.5;  ///< a car's reach from its origin in the plan (the sedan's half length)

/// Seconds until two discs, `relative_m` apart and closing at `relative_mps`, first touch with their
/// edges `reach_m` apart; 0 when they already do, infinity when they never will.
double timeToReach(const Eigen::Vector2d& relative_m, const Eigen::Vector2d& relative_mps, double reach_m) {
  const double c = relative_m.squaredNorm() - reach_m * reach_m;
  if (c <= 0) return 0;
  const double a = relative_mps.squaredNorm(), b = relative_m.dot(relative_mps);
  if (a <= 0 || b >= 0) return std::numeric_limits<double>::infinity();  // not closing
  const double discriminant = b * b - a * c;
  if (discriminant < 0) return std::numeric_limits<double>::infinity();  // passes by
  return (-b - std::sqrt(discriminant)) / a;
}

Eigen::Vector2d startVelocity(const VehicleConfig& v) {
  const double heading = v.start.heading_deg * kDegree;
  const Eigen::Vector2d forward(std::cos(heading), std::sin(heading)), left(-forward.y(), forward.x());
  return (v.start.speed_kmh * forward + v.start.lateral_speed_kmh * left) / 3.6;
}

/// How far an obstacle reaches from its position in the ground plane [m].
double obstacleReach(const ObstacleConfig& o) {
  switch (o.type) {
    case ObstacleType::Post:
    case ObstacleType::Vegetation:
      return o.radius_m;
    case ObstacleType::Wall:
    case ObstacleType::Box:
      return 0.5 * std::hypot(o.size_m.x(), o.size_m.y());
    case ObstacleType::Ramp:
      return 0.5 * std::hypot(o.length_m, o.width_m);
    case ObstacleType::Mesh:
      return 1.0;
  }
  return 1.0;
}

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
  // "Deformation levels", with the commands). K changes the skin's cost, not the step's. A coarser level
  // than fast is not worth having: at 30 points a car meeting another costs twice fast's (its larger
  // triangles carry more face samples, each an MPR query against the other car's hull).
  static const std::vector<DeformationLevel> levels = {
      {"fast", 60, 4, 2, 1, 0.013, 0.021, 0.096},    {"balanced", 60, 8, 4, 2, 0.044, 0.056, 0.25},
      {"accurate", 250, 8, 4, 2, 0.166, 0.18, 1.25}, {"fine", 500, 8, 4, 2, 0.31, 0.34, 2.9},
      {"finest", 1000, 8, 4, 2, 0.61, 0.66, 5.2},
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

BudgetPlan planDeformationBudget(const SceneConfig& scene, double budget_ms, int internal_steps) {
  const std::vector<DeformationLevel>& levels = deformationLevels();
  const std::size_t n = scene.vehicles.size();
  const double steps = std::max(internal_steps, 1);
  BudgetPlan plan;
  plan.budget_ms = budget_ms;
  plan.cars.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    BudgetChoice& choice = plan.cars[i];
    const VehicleConfig& v = scene.vehicles[i];
    const Eigen::Vector2d p = v.start.position_m.head<2>(), u = startVelocity(v);
    auto consider = [&](double t, Meets what) {
      if (t < choice.first_contact_s) {
        choice.first_contact_s = t;
        choice.meets = what;
      }
    };
    for (std::size_t j = 0; j < n; ++j)
      if (j != i)
        consider(timeToReach(scene.vehicles[j].start.position_m.head<2>() - p,
                             startVelocity(scene.vehicles[j]) - u, 2 * kCarReach_m),
                 Meets::Car);
    for (const ObstacleConfig& o : scene.obstacles)
      consider(timeToReach(o.position_m.head<2>() - p, -u, kCarReach_m + obstacleReach(o)), Meets::Obstacle);
    choice.camera_distance_m = cameraDistance(scene, i);
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const BudgetChoice &x = plan.cars[a], &y = plan.cars[b];
    if (x.first_contact_s != y.first_contact_s) return x.first_contact_s < y.first_contact_s;
    return x.camera_distance_m < y.camera_distance_m;
  });
  std::vector<std::size_t> chosen(n, 0);  // index into levels
  auto cost = [&](std::size_t car, std::size_t level) {
    const DeformationLevel& l = levels[level];
    const Meets meets = plan.cars[car].meets;
    return (meets == Meets::Car ? l.car_ms : meets == Meets::Obstacle ? l.obstacle_ms : l.driving_ms) * steps;
  };
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) total += cost(i, 0);
  plan.met = total <= budget_ms;
  // One level up at a time, in priority order, round after round, while the budget has room: the first
  // cars get the finer levels, and no car is left at the coarsest while another takes the finest.
  for (bool raised = plan.met; raised;) {
    raised = false;
    for (const std::size_t car : order) {
      const std::size_t next = chosen[car] + 1;
      if (next >= levels.size() || total - cost(car, chosen[car]) + cost(car, next) > budget_ms) continue;
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
  }
}

}  // namespace scenes
