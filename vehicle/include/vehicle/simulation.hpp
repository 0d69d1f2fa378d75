#pragma once
// A World whose cars may deform: every deformable car carries a deform::DeformableBody (its control
// points in the vehicle frame) coupled to its ODE chassis (DESIGN.md section 5, the crush coupling).
//
// Per step: ODE (wheel forces, collisions, the chassis's crush force of the previous step), then for
// every deformable car: the obstacles it touches, expressed in its vehicle frame, push its control points
// back out to their surfaces (deform's contact projection: exact for primitives, libccd MPR against the
// support function otherwise); the body spreads that into an elastic-plastic dent.
//
// Couplings (DeformationSettings::coupling):
//  - Crush (default): ODE contacts of the chassis with what it hits are rigid only beyond a crush
//    allowance (a backstop); within it the car moves on into the obstacle and is decelerated by the force
//    the body's spokes carry into the core (the crumple's resistance), so the kinetic energy goes into
//    plastic work. The collision hull is rebuilt from the dented body once the contact has ended (never
//    from the instantaneous points during it: that would cancel the decelerating force, DESIGN.md sec. 5).
//  - Visual (Kenwright 2015): ODE's rigid contacts stop the car as an undamaged one, and the motion is
//    not changed by the damage. The body meets what the car hits where the car would be without those
//    contacts (its ghost: the velocity they took from the chassis, slowed by the body's push), so the
//    dent is the crush coupling's for the same impact.
//
// Contract names (the scene runner's): WorldSettings, CarId, CarStart, VehicleSettings are world.hpp's
// and vehicle_settings.hpp's types of those names.
#include <vehicle/material_map.hpp>
#include <vehicle/world.hpp>

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/deformable_body.hpp>
#include <deform/material.hpp>
#include <deform/skin.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vehicle {

enum class Coupling : uint8_t {
  Crush,   ///< the crumple absorbs the kinetic energy (default)
  Visual,  ///< the paper: motion unaffected by damage; the body dented by the car's ghost (no rigid contact)
};

/// Per-car deformation settings (scene keys vehicle.deformation.*). The material is given in physical
/// units (deform/material.hpp) and each constraint takes its share from the geometry it stands for, so
/// the crush does not depend on the level of detail, and nothing is scaled by the car's mass: a heavier
/// car with the same material crushes more. The defaults are the calibration of docs/CRASH_CALIBRATION.md
/// (the built-in 1500 kg sedan against 56 km/h full-width rigid-barrier tests).
/// What stops a crushing car once its crush stroke is used up (DeformationSettings::backstop).
enum class Backstop { RigidParts, ShrunkHull };

struct DeformationSettings {
  std::size_t control_points = 60;  ///< control points of the deformable body (4 .. 5000) [-]
  double alpha = 3.5;               ///< skin: inverse-distance exponent for the render mesh [-]
  std::size_t k_nearest = 8;        ///< skin: control points per render vertex (0 = dense) [-]
  /// skin: how the render vertices' weights are chosen (idw: the paper's; mls: affine maps exact).
  deform::SkinMethod skin_method = deform::SkinMethod::idw;
  int substeps = 4;    ///< deform substeps per physics step (>= 1) [-]
  int iterations = 2;  ///< Gauss-Seidel sweeps per substep (>= 1) [-]
  /// Visual constraint: no control point moves further than this from its rest position [m].
  double max_deviation_m = 1.0;
  /// The body's material (crush strength, shell membrane and bending, yield, hardening).
  deform::Material material = sedanMaterial();
  /// Named regions of the body with their own values of the material (material_map.hpp), e.g.
  /// sedanMaterialMap(). Empty (the default until that map is calibrated, docs/CRASH_CALIBRATION.md):
  /// one material everywhere.
  std::vector<RegionMaterial> regions;
  /// Share of the vehicle mass carried by the control points in the deformation dynamics [-]: the
  /// crushable body shell (a body-in-white is about a quarter of a car's kerb mass). (0, 1].
  double shell_mass_fraction = 0.25;
  /// Viscous damping of the control points' motion relative to the chassis [1/s].
  double damping = 80.0;
  /// Coulomb friction of control points sliding on what they hit [-].
  double contact_friction = 0.3;
  /// Fastest a control point that begins a substep inside an obstacle is pushed out of it [m/s]
  /// (deform::SolverParams::max_depenetration_mps).
  double max_depenetration_mps = 10.0;
  /// Longest substep of a step with an obstacle or another deformable car in contact [s]
  /// (deform::SolverParams::longest_contact_substep_s); 0: 0.5 ms from 250 control points up, else the
  /// substeps alone (measured at 120 Hz, docs/CRASH_CALIBRATION.md, "Two cars, one solve").
  double longest_contact_substep_s = 0;
  /// Crush with backstop ShrunkHull: intrusion of the chassis hull into what it hits beyond which ODE's rigid
  /// contact takes over (the crush stroke is used up: an engine block, a bulkhead) [m]. Kept below
  /// max_deviation_m.
  double crush_allowance_m = 0.8;
  /// Crush: what stops the intrusion once the crush stroke is used up. RigidParts (the default): the
  /// car's rigid parts, `rigid_parts`; ShrunkHull: the hull shrunk by crush_allowance_m.
  Backstop backstop = Backstop::RigidParts;
  /// The rigid parts, boxes in fractions of the car's bounding box (material_map.hpp: x 0 at the rear to
  /// 1 at the front, y right to left, z bottom to top).
  std::vector<deform::Aabb> rigid_parts = sedanRigidParts();
  /// Visual coupling only: scale of the chassis's inertial (fictitious) forces on the control points [-]
  /// (crush always uses 1, the shell's real inertia).
  double inertial_scale = 0.0;
  Coupling coupling = Coupling::Crush;
  /// Force-limited constraints (deform::SolverParams::yield_limited): no constraint carries more than its
  /// yield force, and a held point at its cap stops the chassis rigidly. Off: the solve carries whatever
  /// force its iterations reach (the older model, kept for comparison).
  bool yield_limited = true;
  /// Crush columns held at a rest place, resisting by the volume their patch sweeps
  /// (deform::BodyDescription::anchored_columns); off: spokes along the patch's normal (the older model).
  /// With yield_limited, the wall crash converges in N (docs/CRASH_CALIBRATION.md).
  bool anchored_columns = true;
  /// Idle cars cost nothing (DESIGN.md section 8; issue 42): a car with nothing near it (a broad phase
  /// over the bounding boxes of every car's control points and every obstacle, grown by the step's travel)
  /// whose points have been at rest relative to the chassis for four of the damping's time constants
  /// (0.05 s at the default 80 1/s) falls asleep, and stays asleep whatever the chassis's accelerations
  /// do: the shell is carried rigidly and no solver step runs until something comes near. On by default. Off
  /// (the behaviour before issue 42, kept for comparison): the body falls asleep after
  /// deform::SolverParams::sleep_delay_s of quiet and wakes on any change of its inertial load above
  /// deform::SolverParams::wake_load_mps2, which a car on its suspension does nearly every step.
  bool skip_when_idle = true;
  /// Refinement at run time (deform/refinement.hpp): where an obstacle comes within the step's reach of
  /// the control surface and its surface curves more tightly than the patch it meets (a pole, a box's
  /// edge, not a flat wall or the ground), the patch splits until its edges are half the obstacle's radius
  /// of curvature there, and never shorter than contact_edge_m. A refined patch stays refined. Off: the
  /// start level throughout.
  bool refine = false;
  double contact_edge_m = 0.05;  ///< the shortest edge refinement makes [m]; > 0
  /// Refinement stops at this many control points; the summary says when it did.
  std::size_t max_control_points = 2000;

  /// The calibrated material of the built-in sedan (docs/CRASH_CALIBRATION.md).
  static deform::Material sedanMaterial();
};

/// Throws deform::InputError naming the member ("vehicle.deformation.<member>") for a value out of range.
void checkDeformationSettings(const DeformationSettings& settings);

/// The longest substep deform takes in a step with an obstacle or another car in contact [s]
/// (DeformationSettings::longest_contact_substep_s, or its default by the control points); HUGE_VAL for
/// none (the substeps alone).
double contactSubstep_s(const DeformationSettings& settings);
/// The same for a body of `control_points` points (a refined body's, re-derived at each refinement).
double contactSubstep_s(const DeformationSettings& settings, std::size_t control_points);

/// Energy of a run since the car's first impact [J], in the world frame. Every term is measured on its
/// own: the whole car's kinetic energy (ODE chassis plus the shell's point masses), the work of every
/// force ODE applies to the chassis, and in the body its plastic work (force x plastic flow), viscous
/// loss, contact loss (each contact correction's kinetic energy in the obstacle's frame) and elastic
/// energy. balance_error_J is what those leave unexplained; none of them is defined as a remainder.
struct EnergyTerms {
  /// The whole car's kinetic energy (chassis translation + rotation, and the shell's points) at impact [J].
  double kinetic_initial_J = 0;
  double plastic_work_J = 0;  ///< plastic work done in the body since impact (deform) [J]
  double damping_loss_J = 0;  ///< the body's viscous loss since impact (deform) [J]
  double contact_loss_J = 0;  ///< kinetic energy the obstacles' contacts took from the points (deform) [J]
  /// Elastic energy the body holds now less at impact, at the forces its constraints carry (sum 1/2 alpha
  /// F^2, deform::DeformableBody::carriedElasticEnergy_J) [J].
  double elastic_energy_J = 0;
  /// Work the obstacles did on the body, in the chassis's frame (StepReport::contact_work_J) [J].
  double contact_work_J = 0;
  /// Work the chassis's inertial forces and gravity did on the body in its frame
  /// (StepReport::inertial_work_J) [J].
  double inertial_work_J = 0;
  /// Work the obstacles' own motion did on the car through its body, in the world [J]: zero for what stands
  /// still (a wall, a post), what another car or a falling tree put in (or took out) otherwise.
  double obstacle_work_J = 0;
  /// damping_loss_J + contact_loss_J + other_work_J: what left the car other than as plastic work [J].
  double dissipated_J = 0;
  double kinetic_final_J = 0;  ///< the whole car's kinetic energy now [J]
  /// Kinetic energy the body's reaction (the momentum it handed the chassis, step by step) took from the
  /// ODE chassis [J].
  double crush_work_J = 0;
  /// Work taken from the car by every force ODE applies: tyres and suspension, ODE's rigid contacts (the
  /// backstop, the ground), drag, and gravity on the whole car (raising it) [J].
  double other_work_J = 0;
  double body_energy_J = 0;  ///< elastic plus kinetic energy held in the body relative to the chassis now [J]
  /// kinetic_initial + obstacle work - kinetic_final - plastic - damping - contact loss - elastic - other
  /// work [J]: the energy no measured term explains (the XPBD solve's own numerical loss,
  /// docs/CRASH_CALIBRATION.md).
  double balance_error_J = 0;
};

/// What a run did to one car (all since its first impact; zeros before it).
struct CrashMetrics {
  /// Closing speed along the impact normal at impact [m/s]: the depth-weighted contact normal over the
  /// first 10 ms of contact with what was hit first, made horizontal when it is mostly so.
  double impact_speed_mps = 0;
  /// Largest separating speed along that normal while in contact with what was hit and as the car leaves
  /// it (not what the driver does afterwards) [m/s]; restitution = rebound / impact [-].
  double rebound_speed_mps = 0;
  double restitution = 0;
  /// Permanent crush as crash tests measure it: the intrusion of the struck end's profile at six equally
  /// spaced stations across the width, at the height of its most protruding rest point (the bumper),
  /// averaged [m] and the
  /// largest [m] (of the control surface, from the rest shape to the shape now).
  double residual_crush_m = 0;
  double max_residual_crush_m = 0;
  /// The six stations' intrusions behind that average, in order along up x impact direction (a frontal
  /// impact: from the car's right, -y, to its left), NaN where a station's line misses the surface [m];
  /// and the height they are measured at [m, vehicle frame]. Empty and 0 before an impact.
  std::vector<double> crush_profile_m;
  double crush_height_m = 0;
  /// The horizontal unit direction out of the struck end that those stations look along (vehicle
  /// frame; +x for a frontal impact) [-].
  Eigen::Vector3d impact_direction_vehicle{1, 0, 0};
  /// Deepest dent: the largest displacement of a control point against the impact direction now [m]
  /// (a pole's narrow dent can fall between the six stations).
  double max_dent_m = 0;
  /// Largest displacement of the car into what it hit since first contact (the dynamic crush) [m].
  double max_dynamic_crush_m = 0;
  /// Volume the control surface encloses at rest less what it encloses now [m^3]: the crushed volume,
  /// which a material of crush strength sigma absorbs about sigma x volume for. Unlike a depth it does not
  /// depend on how wide the level of detail spreads a dent (a pole's notch at fine N, a shallow trough at
  /// coarse N).
  double crushed_volume_m3 = 0;
  EnergyTerms energy;
  double max_deviation_m = 0;  ///< largest |c_i - c_i0| ever [m]
  double max_penetration_m =
      0;                   ///< largest depth of a control point left inside an obstacle after a step [m]
  bool tunnelled = false;  ///< the chassis's origin passed into or through a wall or post within a step
  /// A non-finite value or one beyond 1e10 in the car or its body, energy created past the energy
  /// watch's tolerance, or the car rising past its ballistic bound (Simulation::energyWatch).
  bool diverged = false;
  /// When it first diverged [s] and what: "control point N", "chassis", "energy created: ..." or
  /// "rose ... past its ballistic bound ..." (empty while it has not).
  double diverged_at_s = 0;
  std::string diverged_what;
  bool impacted = false;  ///< the car has hit something (not the ground)
};

/// Stage timings of the last step [ms], for the runner's timing_ms. Each is wall time: with threads,
/// a parallel phase's time is split over its stages in proportion to their time summed over the cars.
struct StepTimings {
  double tyres_ms = 0;     ///< ODE side: wheel raycasts, suspension, tyre forces (WorldTimings) [ms]
  double collide_ms = 0;   ///< ODE's collision detection [ms]
  double solve_ms = 0;     ///< ODE's quick step [ms]
  double deform_ms = 0;    ///< every car's body step (deform's XPBD substeps) [ms]
  double coupling_ms = 0;  ///< what the cars touch into deform's inputs, the reaction back to ODE [ms]
  double metrics_ms = 0;   ///< crash metrics and the energy account [ms]
  double physics_ms() const { return tyres_ms + collide_ms + solve_ms; }  ///< ODE's whole step [ms]
};

/// The share of the energy through a run that it may create before the energy watch marks it diverged
/// (Simulation::energyWatch; DESIGN.md section 7) [1].
inline constexpr double kEnergyWatchTolerance = 0.05;

class Simulation {
 public:
  /// Throws deform::InputError as World's constructor.
  explicit Simulation(const WorldSettings& settings = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  World& world();
  const World& world() const;

  /// A car whose body deforms: control mesh (deformation.control_points, even LOD), masses and body
  /// from `model`'s body mesh; the chassis as World::addCar. Throws deform::InputError for bad settings.
  CarId addDeformableCar(const deform::VehicleModel& model, const VehicleSettings& car, const CarStart& start,
                         const DeformationSettings& deformation = {});

  /// Threads the cars' deformation steps run on (>= 1; 1: all on the calling thread). ODE's step stays
  /// on the calling thread. The state is bit for bit the same on any count: every car's inputs are taken
  /// from the world as ODE's step left it (reads only), cars whose bodies can meet are stepped as one
  /// group (deform::stepGroup; each group touches only its own cars), and the reactions are handed to ODE
  /// in the order of the cars. Throws deform::InputError naming "threads" for a count below 1.
  void setThreads(int threads);
  int threads() const;

  /// One fixed physics step: ODE, then every car's deformation (and crush coupling; two deformable cars
  /// in the crush coupling that can meet are one solve, each meeting the other's surface as it deforms).
  void step();
  /// Steps covering `duration_s` at the fixed rate; returns how many.
  int run(double duration_s);

  std::size_t deformableCount() const;
  bool isDeformable(CarId car) const;
  /// Control-point displacements c_i - c_i0 in the vehicle frame [m], one per control point (for the
  /// skin). Throws std::out_of_range for a car that does not deform.
  std::vector<Eigen::Vector3d> controlDisplacements(CarId car) const;
  /// Rest control points (vehicle frame) — for building the render skin.
  const std::vector<Eigen::Vector3d>& controlRestPoints(CarId car) const;
  /// Current control points (vehicle frame) [m].
  const std::vector<Eigen::Vector3d>& controlPoints(CarId car) const;
  /// The control mesh the body was built from (rest shape, triangles).
  const deform::ControlMesh& controlMesh(CarId car) const;
  const DeformationSettings& deformationSettings(CarId car) const;
  /// The car's deformable body (settings and state), for measurements.
  const deform::DeformableBody& body(CarId car) const;

  CrashMetrics metrics(CarId car) const;
  /// What refinement (DeformationSettings::refine) did to car's body so far.
  struct Refinement {
    std::size_t control_points = 0;  ///< now
    uint64_t refinements = 0;        ///< steps whose contacts split the surface
    bool bounded = false;            ///< a split was refused at max_control_points
  };
  Refinement refinement(CarId car) const;
  /// Steps in which car's body ran deform's solver, and steps it skipped at no solver cost (its body
  /// asleep: nothing touching it, its points at rest, the chassis's load unchanged; the shell is carried
  /// rigidly, which is exactly what the solver would do then). Counted since the simulation was built.
  struct DeformCounts {
    uint64_t steps = 0;
    uint64_t skipped = 0;
  };
  DeformCounts deformCounts(CarId car) const;
  /// The energy watch's account of the whole run (every car and free obstacle), from the end of its
  /// first step: the most energy created beyond none (mechanical energy and the bodies' booked losses
  /// against what the run started with and the engines put in), the energy that went through the run
  /// (its kinetic energy, the engines' work, the potential energy given up), and the engines' work [J].
  /// A run whose created energy passed kEnergyWatchTolerance of that is marked diverged
  /// (CrashMetrics::diverged).
  struct EnergyWatchReport {
    double largest_created_J = 0;
    double largest_created_share = 0;  ///< over the energy through the run when it was largest [1]
    double through_J = 0;
    double drive_work_J = 0;
  };
  EnergyWatchReport energyWatch() const;
  StepTimings lastTimings() const;
  /// Everything that decides the future, between steps: the world's (World::saveState) and per
  /// deformable car its body's state (deform::saveState), the crush coupling's memory (hull dirty, quiet
  /// steps, the chassis's velocities after the last step) and the crash metrics with their accumulators
  /// (so a resumed run reports what the uninterrupted one does).
  void saveState(StateWriter& out) const;
  /// Puts back what saveState wrote into a simulation built the same way. Throws deform::InputError
  /// (through `in`) for bytes that do not fit it.
  void restoreState(StateReader& in);
  /// FNV-1a (64 bit) over saveState's bytes.
  uint64_t stateHash() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The permanent-crush measurement of CrashMetrics on its own: profile of `mesh`'s triangles with the
/// points `points_m` along `direction` (horizontal, vehicle frame, pointing out of the struck end) at
/// height z_m, at `stations` equally spaced positions across the width of the rest shape; returns the
/// intrusion per station (rest profile minus profile now) [m], in order across the width, NaN at a
/// station whose line misses the surface (at rest or now).
std::vector<double> crushProfile(const deform::ControlMesh& mesh,
                                 const std::vector<Eigen::Vector3d>& points_m,
                                 const Eigen::Vector3d& direction, double z_m, int stations = 6);

/// The crash test's whole measurement of a closed surface (`triangles` over `rest_m` at rest and `now_m`
/// now), looking along `direction` out of the struck end: crushProfile at the height of the rest point
/// that protrudes most along `direction` (the bumper, for a frontal impact), with the stations' mean and
/// largest (those whose line meets the surface) [m].
struct CrushStations {
  std::vector<double> profile_m;
  double height_m = 0;
  double mean_m = 0;
  double max_m = 0;
};
CrushStations crushStations(const std::vector<std::array<uint32_t, 3>>& triangles,
                            const std::vector<Eigen::Vector3d>& rest_m,
                            const std::vector<Eigen::Vector3d>& now_m, const Eigen::Vector3d& direction);

/// The same measurement of any closed surface: `triangles` over the points `rest_m` at rest and `now_m`
/// now (the render mesh's vertices, for the crush of the car's own surface, which unlike the control
/// surface is the same at every level of detail). The stations span the width of `rest_m`.
std::vector<double> crushProfile(const std::vector<std::array<uint32_t, 3>>& triangles,
                                 const std::vector<Eigen::Vector3d>& rest_m,
                                 const std::vector<Eigen::Vector3d>& now_m, const Eigen::Vector3d& direction,
                                 double z_m, int stations = 6);

}  // namespace vehicle
