#pragma once
// Levels of detail of a car's deformation, with their measured cost, and a deformation budget shared by
// every car of a scene (scene key deformation_budget_ms, sandbox run --budget-ms): each car is modelled
// only as finely as the budget allows, the cars the script crashes first and those near the camera first.
#include <scenes/scene.hpp>

#include <deform/mesh.hpp>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace scenes {

/// One level of detail: the knobs that set a car's deformation cost, and that cost as measured.
struct DeformationLevel {
  std::string name;
  std::size_t control_points = 60;
  int k_nearest = 8;
  int substeps = 4;
  int iterations = 2;
  /// deform's wall time per physics step of one car whose body is awake, measured on the project's 2-core
  /// machine at 500 Hz on one thread [ms]: driving with nothing near it, against an obstacle (the 56 km/h
  /// wall crash) and against another car's body (car_to_car, the dearest contact: the other car's hull is
  /// met through libccd's MPR).
  double driving_ms = 0;
  double obstacle_ms = 0;
  double car_ms = 0;
};

/// What a car is expected to meet first, which sets its cost in the budget.
enum class Meets : uint8_t { Nothing, Obstacle, Car };

/// The levels, coarsest first. The presets `fast`, `balanced` and `accurate` are three of them: this
/// table is the one place their knobs are set.
const std::vector<DeformationLevel>& deformationLevels();

/// The level called `name`, or nullptr.
const DeformationLevel* deformationLevel(const std::string& name);

/// Sets `level`'s knobs (control points, K, substeps, iterations) on `settings`.
void applyLevel(const DeformationLevel& level, vehicle::DeformationSettings& settings);

/// How much more a step against an obstacle costs than the level's obstacle_ms (measured at 500 Hz, 2 ms
/// world steps) for a car with `settings` at `level` in world steps of `step_s` [s]: the substeps the
/// contact substep cap (vehicle::contactSubstep_s) adds over the level's own, 17 / 4 for a 250-point
/// level at 120 Hz; 1 where the cap adds none.
double contactCostScale(const DeformationLevel& level, const vehicle::DeformationSettings& settings,
                        double step_s);

/// What the budget chose for one car.
struct BudgetChoice {
  std::string level;
  double estimated_ms = 0;  ///< the level's cost per physics step, for what the car meets [ms]
  Meets meets = Meets::Nothing;
  /// When the car first touches another car or an obstacle (not the ground or a ramp) in the scene played
  /// once with rigid cars along their drive scripts (rehearseFirstContacts), over the scene's duration up
  /// to kRehearsal_s [s]; infinity when it does not.
  double first_contact_s = std::numeric_limits<double>::infinity();
  double camera_distance_m = 0;  ///< from the camera's eye (0 for the car a chase camera follows) [m]
  std::size_t priority = 0;      ///< 0 is served first
};

/// A budget's outcome: the level of every car and what they cost together.
struct BudgetPlan {
  double budget_ms = 0;            ///< per physics step, every car together [ms]
  double estimated_ms = 0;         ///< the chosen levels' cost per physics step, every body awake [ms]
  bool met = true;                 ///< false: the coarsest level for every car already costs more
  std::vector<BudgetChoice> cars;  ///< in the scene's order
};

/// How far ahead the budget's rehearsal looks [s].
inline constexpr double kRehearsal_s = 30.0;

/// When each car first touches something it can crash into, and what.
struct FirstContact {
  double time_s = std::numeric_limits<double>::infinity();  ///< infinity: never within the horizon [s]
  Meets meets = Meets::Nothing;
};

/// Every vehicle's model, in order (vehicles with the same mesh spec share one).
std::vector<std::shared_ptr<const deform::VehicleModel>> loadVehicleModels(const SceneConfig& scene);

/// The scene played with rigid cars (ODE's chassis and hull, no deformable body) along their drive
/// scripts, `internal_steps` world steps per physics step, up to `horizon_s` or until every car has met
/// something: each car's first contact with another car (Car) or an obstacle (Obstacle; the ground and
/// ramps do not count). `models`: each vehicle's model, in order. Until its first contact a car moves as
/// it does in the run itself, so a turn, a lane change or a braking in the script is followed.
std::vector<FirstContact> rehearseFirstContacts(
    const SceneConfig& scene, const std::vector<std::shared_ptr<const deform::VehicleModel>>& models,
    int internal_steps, double horizon_s);

/// Chooses a level per car so that their cost per physics step (`internal_steps` world steps each),
/// every body awake and each car charged for what it meets first in the rehearsal (rehearseFirstContacts,
/// over the scene's duration up to kRehearsal_s: another car, an obstacle, or nothing), stays within
/// `budget_ms`. Every car starts at the coarsest level; then, round after round in priority order (the car
/// that crashes first, then the one nearest the camera), each goes one level finer while the budget has
/// room. When even the coarsest levels exceed it, every car keeps the coarsest and `met` is false.
/// `models`: the vehicles' models when already loaded (else they are loaded here).
BudgetPlan planDeformationBudget(
    const SceneConfig& scene, double budget_ms, int internal_steps = 1,
    const std::vector<std::shared_ptr<const deform::VehicleModel>>* models = nullptr);

/// Sets every car's chosen level on `scene`.
void applyBudget(const BudgetPlan& plan, SceneConfig& scene);

}  // namespace scenes
