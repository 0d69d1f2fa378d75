#pragma once
// Playing a scene, without any rendering: the simulation (World plus deformable cars) built from the
// scene, stepped at the fixed physics rate with each car's drive script, and what a run reports: the
// crash metrics of every car, the state hash, stage timings and one timeline row per frame.
#include <scenes/car_skin.hpp>
#include <scenes/deformation_budget.hpp>
#include <scenes/drive_script.hpp>
#include <scenes/scene.hpp>
#include <scenes/surface_crush.hpp>

#include <vehicle/simulation.hpp>

#include <deform/builtin_meshes.hpp>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace scenes {

/// Accumulated wall time per stage of a run [ms] (summary.json's timing_ms). The simulation's stages
/// come from vehicle::StepTimings; setup (meshes, builds, world), embed (the render mesh following the
/// control points), render (drawing, PNG, video) and output (timeline rows, summary and files) from
/// whoever does them. total is the whole run; the stages together cover all but a sliver of it.
struct StageTimes {
  double setup_ms = 0;
  double tyres_ms = 0;
  double collide_ms = 0;
  double solve_ms = 0;
  double deform_ms = 0;
  double coupling_ms = 0;
  double metrics_ms = 0;
  double embed_ms = 0;
  double render_ms = 0;
  double output_ms = 0;
  double total_ms = 0;
  /// ODE's whole step: tyres, collide and solve [ms].
  double physics_ms() const { return tyres_ms + collide_ms + solve_ms; }
  /// The deformable bodies' share: deform, coupling and metrics [ms].
  double deformation_ms() const { return deform_ms + coupling_ms + metrics_ms; }
  /// Every named stage [ms] (what the coverage of total_ms is measured by).
  double stages_ms() const {
    return setup_ms + physics_ms() + deformation_ms() + embed_ms + render_ms + output_ms;
  }
};

/// A scene's slower physics rate is taken in internal steps of at most 1 / this rate [Hz]. When the crush
/// force acted one step late, longer steps created energy (plastic work 10 % above the impact energy at
/// 60 Hz, docs/STABILITY.md); with the reaction in the same step a real 60 Hz step closes its energy
/// balance (+1.5 %) but crushes the sedan 0.614 m at 56 km/h against 0.377 m at 500 Hz: a crash of a few
/// steps is not resolved.
inline constexpr double kMinInternalRate_hz = 120.0;

class SceneRun {
 public:
  /// Loads the meshes and builds the world. Throws deform::InputError naming the scene file and key
  /// for a mesh that cannot be read or settings the vehicle side refuses.
  explicit SceneRun(SceneConfig scene);
  ~SceneRun();
  SceneRun(const SceneRun&) = delete;
  SceneRun& operator=(const SceneRun&) = delete;

  const SceneConfig& scene() const { return scene_; }
  vehicle::Simulation& simulation() { return *simulation_; }
  const vehicle::Simulation& simulation() const { return *simulation_; }

  std::size_t carCount() const { return cars_.size(); }
  vehicle::CarId carId(std::size_t car) const { return cars_[car].id; }
  /// The car's model as loaded (render mesh and wheels, vehicle frame).
  const deform::VehicleModel& model(std::size_t car) const { return *cars_[car].model; }
  /// The crush of car `car`'s own surface now (scenes::surfaceCrush): its render mesh moved by its skin,
  /// built through `skins` (cars of one build share it); empty before the car's first impact.
  vehicle::CrushStations surfaceCrush(std::size_t car, SkinCache& skins) const;
  /// Obstacle id in the world of the scene's obstacle `index`.
  vehicle::ObstacleId obstacleId(std::size_t index) const { return obstacle_ids_[index]; }

  double time_s() const;
  uint64_t steps() const;
  /// Fixed steps the whole scene takes: round(duration_s * physics_hz).
  uint64_t totalSteps() const { return total_steps_; }
  /// Internal simulation steps per scene step: 1 at 120 Hz and above, else the fewest that make each
  /// internal step at most 1/kMinInternalRate_hz s.
  int physicsSubsteps() const { return physics_substeps_; }
  /// The deformation budget's choice of levels (scene key deformation_budget_ms), if the scene has one.
  const std::optional<BudgetPlan>& budgetPlan() const { return budget_plan_; }
  bool finished() const { return steps() >= total_steps_; }

  /// One physics step with every car's drive inputs (does nothing once finished).
  void step();
  /// From the next step on, car `car` takes `input` instead of its drive script (a driver in the loop:
  /// the Python module's drive()); std::nullopt hands it back to the script. The override is an input
  /// from outside, like the script's keys: it is neither in stateHash() nor in the state file.
  void overrideDriverInput(std::size_t car, std::optional<vehicle::DriverInput> input);
  /// The input that overrides car `car`'s script, if any.
  const std::optional<vehicle::DriverInput>& driverOverride(std::size_t car) const {
    return cars_[car].override_input;
  }
  /// Steps until the simulated time reaches t_s (within half a step) or the scene ends.
  void stepUntil(double t_s);
  /// Steps to the end of the scene.
  void runToEnd();
  /// A frame of dt_s from a frame clock (a game loop): takes as many fixed steps as the frames so far
  /// add up to (fix-your-timestep), so a long frame (a 100 ms hitch) gives the same state as many short
  /// ones. Returns the steps taken. Throws deform::InputError naming "dt_s" for zero, negative or
  /// non-finite dt_s.
  int advance(double dt_s);

  /// Physics and deform times so far; embed and render are the caller's to add.
  StageTimes& times() { return times_; }
  const StageTimes& times() const { return times_; }

  /// A non-finite or huge value in any car or body so far.
  bool diverged() const;
  /// What diverged first and when, e.g. "sedan: control point 12 at t = 0.532 s"; empty if nothing did.
  std::string divergence() const;

  /// FNV-1a (64 bit) over everything that decides the rest of the run: the simulation's state
  /// (vehicle::Simulation::saveState: time, step counter, every body, coupling and metric) and every
  /// drive script's speed controller and advance()'s frame clock. What summary()'s state_hash shows.
  uint64_t stateHash() const;
  /// The state file of the run now (scenes/README.md, "Save and resume"): magic, format version,
  /// payload length and checksum, then the scene's name and settings_hash and the state stateHash covers.
  std::vector<uint8_t> stateFile() const;
  /// Writes stateFile() to `path` atomically. Throws std::runtime_error naming the path when it cannot.
  void saveState(const std::string& path) const;
  /// Continues from `bytes`, a state file of this scene with these settings (`name` names it in
  /// messages). Throws deform::InputError "<name>: ..." for a file that is truncated, corrupted, of a newer
  /// format version, of another scene or of other settings; nothing is changed then. (A file that passes
  /// those checks but does not fit the run throws too and leaves the run unusable.)
  void restoreState(std::span<const uint8_t> bytes, const std::string& name);
  /// restoreState from the file at `path` (InputError naming it when it cannot be read).
  void restoreState(const std::string& path);

  /// The run's figures: car 0's metrics at the top level (impact_speed_mps, ..., energy, tunnelled,
  /// diverged of any car), every car's under "cars", state_hash (16 hex digits), steps, timing_ms.
  nlohmann::json summary() const;

  /// Timeline columns (time, step, per car: position, speed, inputs, deviation, crush, plastic work).
  std::vector<std::string> timelineColumns() const;
  /// Their values now.
  std::vector<double> timelineValues() const;

 private:
  struct Car {
    vehicle::CarId id = 0;
    std::shared_ptr<const deform::VehicleModel> model;  ///< shared by the cars of the same mesh spec
    DrivePlayer driver;
    double lateral_speed_mps = 0;                        ///< pushed in on the first step
    std::optional<vehicle::DriverInput> override_input;  ///< replaces the script while set
  };
  SceneConfig scene_;
  /// One simulation step with every car's drive inputs.
  void internalStep();
  /// Throws deform::InputError naming both when a car overlaps an obstacle or another car at the start.
  void refuseStartingOverlaps() const;
  /// The state as bytes (state_file.cpp): for the state file, or (for_hash) what stateHash covers.
  std::vector<uint8_t> stateBytes(bool for_hash) const;

  std::unique_ptr<vehicle::Simulation> simulation_;
  std::vector<Car> cars_;
  std::vector<vehicle::ObstacleId> obstacle_ids_;
  uint64_t total_steps_ = 0;
  int physics_substeps_ = 1;
  std::optional<BudgetPlan> budget_plan_;
  uint64_t steps_at_start_ = 0;  ///< the step counter when this run began (a resumed run's saved one)
  double frame_time_s_ = 0;      ///< sum of advance()'s frames [s]
  StageTimes times_;
};

/// The scene a state file was saved from: the scene file's path as the run had it (SceneConfig::source),
/// so that a run can be resumed without naming its scene again. Throws deform::InputError naming `path`
/// when it cannot be read or is not a state file (the full checks are restoreState's).
std::string stateFileSceneSource(const std::string& path);

/// Threads a run takes when neither the scene nor the command line says: the machine's cores.
int defaultThreads();

/// "0123456789abcdef": a state hash as 16 hex digits.
std::string hashHex(uint64_t hash);

/// CrashMetrics::crush_profile_m as JSON: a number per station, null where the station's line missed
/// the surface (NaN), so that two summaries of the same run compare equal.
nlohmann::json profileJson(const std::vector<double>& profile_m);

/// Writes `text` to `path` atomically (path.tmp, then rename). Throws std::runtime_error naming the path.
void writeFileAtomically(const std::string& path, const std::string& text);

/// The timeline as CSV: a header of `columns`, one line per row.
std::string timelineCsv(const std::vector<std::string>& columns,
                        const std::vector<std::vector<double>>& rows);

}  // namespace scenes
