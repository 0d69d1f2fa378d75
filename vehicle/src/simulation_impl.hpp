#pragma once
// The inside of Simulation (simulation.hpp), shared by its source files: simulation.cpp (the API and the
// step), crush_coupling.cpp (one car's deformation and its reaction on the chassis) and
// crash_metrics_update.cpp (what a run did to a car).
#include <vehicle/simulation.hpp>

#include <vehicle/car_build.hpp>

#include "broad_phase.hpp"
#include "crush_shapes.hpp"

#include <deform/body_settings.hpp>
#include <deform/body_state.hpp>
#include <deform/deformable_body.hpp>
#include <deform/refinement.hpp>

#include <algorithm>
#include <memory>
#include <vector>

namespace vehicle {

/// Kinetic energy of the ODE chassis: translation plus rotation (its inertia in the body axes) [J].
double kineticEnergy(const Car& car);
/// What crushes the body: another car, or an obstacle crushesBody (world.hpp) accepts; in the visual
/// coupling not vegetation, which ODE's rigid hull knocks over.
bool crushable(const World& world, EntityRef e, Coupling coupling);
/// deform's key of a free obstacle (StepInputs::contact_keys): one per entity, never 0.
inline uint64_t freeObstacleKey(EntityRef e) {
  return (uint64_t{e.kind == EntityRef::Kind::Car ? 2u : 1u} << 32) | e.index;
}
/// An obstacle standing on the ground (crush_coupling.cpp).
bool standsOnGround(const ObstacleShape& shape);
/// Whether `point` lies inside the closed outward-wound surface `mesh`, at least `margin_m` from every face.
bool enclosesWithMargin(const deform::ControlMesh& mesh, const Eigen::Vector3d& point, double margin_m);

/// One deformable car: its body and the bookkeeping of the coupling and the metrics.
struct DeformableCar {
  CarId id = 0;
  DeformationSettings settings;
  /// The shared, immutable part (control mesh, masses, body settings, collision hull).
  std::shared_ptr<const CarBuild> build;
  /// build->body_settings, or the car's own once refinement has split its surface.
  std::shared_ptr<const deform::BodySettings> body_settings;
  std::unique_ptr<deform::DeformableBody> body;
  /// Refinement (DeformationSettings::refine): the body's surface hierarchy, from its first split; how many
  /// steps split it, and whether the bound refused a split.
  std::unique_ptr<deform::SurfaceHierarchy> hierarchy;
  uint64_t refinements = 0;
  bool refine_bounded = false;
  CrushShapes shapes;               ///< what the car touches at the end of the step (vehicle frame)
  std::vector<EntityRef> touching;  ///< crushable entities in contact or within reach this step
  /// Of those, what the car met this step: in ODE's contacts, or pushing the body's points (the metrics'
  /// impact and rebound window; one within reach but missed is not an impact).
  std::vector<EntityRef> hit;
  std::size_t in_ode_contact = 0;  ///< the first entries of touching, found in ODE's contacts
  /// Other deformable cars within reach, both in the crush coupling: stepped with this one as a group
  /// (deform::stepGroup), not in touching. Per partner: in ODE's contacts, and whether the bodies' contacts
  /// pushed (set by the group's step).
  std::vector<CarId> partners;
  std::vector<uint8_t> partner_in_ode, partner_pushed;
  /// Its control points in the world before this step's deformation: what other cars dent against
  /// (taken for every car first, so the order cars are stepped in does not matter).
  ObstacleShape world_shape;

  // This step's work (prepareCar, solveCar, finishCar).
  Pose frame;                 ///< the vehicle frame after ODE's step, before the body's reaction
  deform::StepInputs inputs;  ///< what the body steps with
  deform::StepReport report;  ///< what its step handed back

  /// Steps whose body step ran the XPBD solver, and steps it skipped (asleep: no contact, no motion,
  /// the same load; O(1), the shell carried rigidly). Statistics, not state.
  uint64_t deform_steps = 0, deform_steps_skipped = 0;

  // Coupling.
  bool hull_dirty = false;                         ///< dented since the collision hull was last rebuilt
  int quiet_steps = 0;                             ///< steps without a control point in contact
  Eigen::Vector3d previous_velocity_mps{0, 0, 0};  ///< chassis, after the body's reaction last step (world)
  Eigen::Vector3d previous_omega_radps{0, 0, 0};   ///< the same, angular (world)
  /// Visual: the car as it would move without ODE's rigid contact with what it crushes (a "ghost"), relative
  /// to the chassis, vehicle frame. ODE's contact impulses on the chassis go to it (their velocity change is
  /// the ghost's), the body's contact impulses take them back, and what it hits is met where the ghost
  /// would meet it: the dent the crush coupling gives for the same impact, the chassis's motion left to
  /// ODE (advanceGhost and updateGhost, crush_coupling.cpp) [m/s], [m].
  Eigen::Vector3d ghost_velocity_mps{0, 0, 0}, ghost_offset_m{0, 0, 0};
  /// This step's ODE contacts with anything crushable (advanceGhost, after ODE's step): whether there are
  /// any, and the sum of their normals (vehicle frame, out of what the car touches). Not state: each step
  /// finds its own.
  bool ghost_in_ode_contact = false;
  Eigen::Vector3d ghost_contact_normal{0, 0, 0};
  /// Crush: (I_chassis + I_shell)^-1 I_chassis (chassis axes) [-]; its transpose is the chassis's share of
  /// a moment the body hands the core (finishCar), the shell turning with it taking the rest.
  Eigen::Matrix3d chassis_share_of_rotation = Eigen::Matrix3d::Identity();

  // Metrics.
  CrashMetrics metrics;
  Eigen::Vector3d impact_normal{0, 0, 1};  ///< world, out of what it hit
  Eigen::Vector3d impact_direction_vehicle{1, 0, 0};
  EntityRef impact_other;
  double impact_separation_m = 0;  ///< normal . (com - other's interior point) at impact [m]
  Eigen::Vector3d impact_relative_velocity_mps{0, 0, 0};           ///< before the impact step (world) [m/s]
  Eigen::Vector3d impact_com_m{0, 0, 0}, impact_other_m{0, 0, 0};  ///< at impact (world) [m]
  Eigen::Vector3d impact_normal_sum{0, 0, 0};
  int impact_steps = 0;     ///< steps of contact the impact normal has been averaged over
  bool in_contact = false;  ///< in contact with what it hit first, last step (the rebound's window)
  double plastic_at_impact_J = 0;
  double plastic_before_step_J = 0;
  double body_energy_at_impact_J = 0;  ///< elastic + kinetic energy in the body at impact [J]
  double damping_loss_J = 0;           ///< the body's viscous loss since the start [J]
  double damping_at_impact_J = 0;
  double contact_work_J = 0;  ///< deform's, since the start [J]
  double contact_work_at_impact_J = 0;
  double inertial_work_J = 0;  ///< deform's, since the start [J]
  double inertial_work_at_impact_J = 0;
  /// Work the obstacles' motion did on the car through its body, in the world, since the start [J].
  double obstacle_work_J = 0;
  double obstacle_work_at_impact_J = 0;
  /// The chassis's velocity at the core and its turn when the step began (vehicle frame): the frame in
  /// which deform took the obstacles' motion, to take their work back to the world [m/s], [rad/s]. Set by
  /// prepareCar every step, so not part of the saved state.
  Eigen::Vector3d frame_velocity_mps{0, 0, 0}, frame_omega_radps{0, 0, 0};
  double contact_loss_J = 0;  ///< deform's, since the start [J]
  /// The losses of its links to partners (deform::LinkReport, this car the first of the link), which the
  /// partner's contact_loss_J books too, since the start [J].
  double link_loss_counted_twice_J = 0;
  double contact_loss_at_impact_J = 0, contact_loss_before_step_J = 0;
  double elastic_at_impact_J = 0, elastic_before_step_J = 0;  ///< the body's elastic energy [J]
  double step_crush_work_J = 0;  ///< kinetic energy the body's reaction took from the chassis this step [J]
  double step_other_work_J = 0;  ///< work every other force took from it this step [J]
  /// The body's carried elastic energy after its last step that solved (deform::DeformableBody::
  /// carriedElasticEnergy_J), kept here so a restored run reports what the uninterrupted one does [J].
  double elastic_after_step_J = 0;
};

/// The energy watch (energy_watch.cpp; DESIGN.md section 7): every step, the mechanical energy of every
/// car (chassis, shell points, wheels' spin, weight) and free obstacle, plus what the bodies booked as
/// lost (plastic work, viscous and contact losses), may exceed what the run started with and the engines
/// put in by no more than a tolerance; and a car that touches nothing rises no higher than its speed
/// when it left allows. A run that breaks either is marked diverged on the car whose energy rose most.
struct EnergyWatch {
  /// Energy created beyond this share of the energy that went through the run (its kinetic energy at
  /// the start, the engines' work, and the potential energy given up) is a broken run.
  static constexpr double kTolerance = kEnergyWatchTolerance;
  /// ... plus the energy of lifting every mass by this much, so a car settling on its springs (whose
  /// energy is not counted) is not flagged [m].
  static constexpr double kFloorLift_m = 0.05;
  /// A flight may rise this much above its ballistic apex (ODE's integration stays below it) [m].
  static constexpr double kApexSlack_m = 0.02;
  bool started = false;
  double initial_J = 0;              ///< the mechanical energy of everything at the start [J]
  double initial_kinetic_J = 0;      ///< its kinetic part [J]
  double initial_potential_J = 0;    ///< its potential part [J]
  double lowest_potential_J = 0;     ///< the least potential energy of everything so far [J]
  double drive_work_J = 0;           ///< the engines' work on the wheels since the start [J]
  double total_mass_kg = 0;          ///< every car and free obstacle [kg]
  double through_J = 0;              ///< the energy through the run so far (kTolerance) [J]
  double largest_created_J = 0;      ///< the most created energy seen, beyond none (reported) [J]
  double largest_created_share = 0;  ///< that, over the energy through the run [1]
  std::vector<double> car_energy_J;  ///< per CarId: its energy and booked losses after the last step [J]
  std::vector<uint8_t> airborne;     ///< per CarId: touching nothing since `apex_m` was set
  std::vector<double> apex_m;        ///< per CarId: the highest its centre of mass may rise now [m]
};

struct Simulation::Impl {
  World world;
  std::vector<std::unique_ptr<DeformableCar>> cars;
  std::vector<int> index_of;  ///< per CarId: index into cars, -1 when rigid
  StepTimings timings;
  CarBuildCache builds;  ///< one build per mesh and shaping settings, shared by the cars
  int threads = 1;       ///< for the cars' deformation steps (Simulation::setThreads)

  /// The cars (indices into cars, prepared) in groups whose bodies step as one: a car with its partners
  /// and theirs, and the cars pushing the same free obstacle, each group in the cars' order, the groups in
  /// the order of their first car; a car with no partner alone (car_group.cpp).
  std::vector<std::vector<std::size_t>> bodyGroups() const;
  /// This step's boxes in the world, ungrown (updateBoxes, after ODE's step and the cars' snapshots):
  /// per CarId its control points (a deformable car) or hull, per ObstacleId its shape (the ground's is
  /// left empty: a half-space has no box).
  std::vector<Box> car_boxes, obstacle_boxes;
  /// car_boxes by place, and the fastest car, the fastest turn and the largest half-diagonal among them
  /// this step: what bounds how far another car can be and still come within a car's reach
  /// (addApproaching) [m/s], [rad/s], [m].
  BoxGrid car_grid;
  double fastest_car_mps = 0, fastest_turn_radps = 0, largest_half_diagonal_m = 0;
  /// The largest reach of a visual car's ghost this step, |offset| + |velocity| dt (advanceGhost) [m].
  double largest_ghost_m = 0;
  void updateBoxes();
  /// Per car (index into cars): nothing near it this step (simulation_step.cpp's broad phase: boxes of
  /// the control points and obstacles grown by the step's travel; any contact but the ground's counts).
  std::vector<uint8_t> idleCars() const;
  /// Keeps an idle car's body asleep (DeformationSettings::skip_when_idle), or lets it wake as usual.
  void holdAsleep(DeformableCar& dc, bool idle) const;
  /// Whether a body holdAsleep holds asleep sleeps through this step (prepared): asleep, and nothing
  /// to meet, no impulse, no partner (its wake load is never reached).
  static bool sleepsThrough(const DeformableCar& dc) {
    return dc.body->state().sleeping && dc.inputs.contacts.empty() && dc.inputs.impulses.empty() &&
           dc.partners.empty();
  }

  EnergyWatch watch;
  /// Every car's and free obstacle's mechanical energy and booked losses; per car into `per_car_J`
  /// (indexed by CarId), with `kinetic_J` and `potential_J` their sums (energy_watch.cpp).
  double watchedEnergy_J(std::vector<double>& per_car_J, double& kinetic_J, double& potential_J) const;
  /// The whole car's centre of mass and its velocity (world): in Crush, the chassis and the shell's points.
  void wholeCarCentre(CarId c, Eigen::Vector3d& position_m, Eigen::Vector3d& velocity_mps) const;
  /// Starts the watch at the end of the first step (Simulation::step: a scene may push a car in it).
  void startWatch();
  /// The checks after a step; marks the run diverged on the first that fails.
  void checkWatch();

  explicit Impl(const WorldSettings& s) : world(s) {}

  DeformableCar& of(CarId id) const {
    if (id >= index_of.size() || index_of[id] < 0)
      throw std::out_of_range("car " + std::to_string(id) + " does not deform");
    return *cars[static_cast<std::size_t>(index_of[id])];
  }

  /// Per CarId, within a step: the chassis's velocity, turn and centre of mass (world) after ODE's step
  /// (refreshMotion): addApproaching reads every other car's for every car, and ODE's pose costs a
  /// quaternion each time. Every car is prepared before any car's reaction (Simulation::step), so these
  /// hold for the whole of the preparation.
  struct CarMotion {
    Eigen::Vector3d velocity_mps{0, 0, 0}, omega_radps{0, 0, 0}, com_m{0, 0, 0};
  };
  std::vector<CarMotion> car_motion;
  void refreshMotion(CarId c) {
    const Car& car = world.car(c);
    car_motion[c] = {car.velocity_mps(), car.angularVelocity_rad_s(), car.bodyPose().position_m};
  }
  std::vector<Eigen::Vector3d> car_velocity_before;  ///< per CarId: velocity before this step [m/s]
  Eigen::Vector3d velocityBefore(EntityRef e) const {
    if (e.kind == EntityRef::Kind::Car && e.index < car_velocity_before.size())
      return car_velocity_before[e.index];
    return velocityOf(e);
  }

  /// A car's centre of mass, or a free obstacle's (its body's origin) (world) [m].
  Eigen::Vector3d centreOf(EntityRef e) const {
    if (e.kind == EntityRef::Kind::Car) return world.car(e.index).bodyPose().position_m;
    return world.obstaclePose(e.index).position_m;
  }
  /// The velocity of a car's centre of mass, or of a free obstacle's (its body's origin) [m/s].
  Eigen::Vector3d velocityOf(EntityRef e) const {
    if (e.kind == EntityRef::Kind::Car) return world.car(e.index).velocity_mps();
    return world.obstacleVelocity_mps(e.index, centreOf(e));
  }
  /// The velocity of `e`'s material at the world point `p_m` [m/s] (velocityOf plus its turn): a box
  /// falling on a car comes at its own speed, and does its work on the body (EnergyTerms).
  Eigen::Vector3d velocityOf(EntityRef e, const Eigen::Vector3d& p_m) const {
    if (e.kind != EntityRef::Kind::Car) return world.obstacleVelocity_mps(e.index, p_m);
    const Car& car = world.car(e.index);
    return car.velocity_mps() + car.angularVelocity_rad_s().cross(p_m - car.bodyPose().position_m);
  }
  Eigen::Vector3d angularVelocityOf(EntityRef e) const {  ///< (world) [rad/s]
    if (e.kind == EntityRef::Kind::Car) return world.car(e.index).angularVelocity_rad_s();
    return world.obstacleAngularVelocity_radps(e.index);
  }

  /// The shape of `e` in the world; a deformable car as its control points now.
  ObstacleShape worldShapeOf(EntityRef e) const {
    if (e.kind == EntityRef::Kind::Car && e.index < index_of.size() && index_of[e.index] >= 0) {
      const DeformableCar& other = of(e.index);
      if (!other.world_shape.vertices_m.empty()) return other.world_shape;
      return snapshotShape(other);
    }
    return world.shapeOf(e);
  }

  /// A deformable car's control points now, in the world, as a convex shape.
  ObstacleShape snapshotShape(const DeformableCar& dc) const {
    ObstacleShape s;
    snapshotInto(dc, s);
    return s;
  }
  /// The same into `s` (a convex shape, or one snapshotInto wrote before), keeping its storage.
  void snapshotInto(const DeformableCar& dc, ObstacleShape& s) const {
    const Pose pose = world.car(dc.id).vehiclePose();
    const std::vector<Eigen::Vector3d>& points = dc.body->state().positions_m;
    s.type = ShapeType::Convex;
    s.centre_m.setZero();
    s.vertices_m.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      s.vertices_m[i] = pose.toWorld(points[i]);
      s.centre_m += s.vertices_m[i];
    }
    s.centre_m /= static_cast<double>(s.vertices_m.size());
  }

  /// The whole car's kinetic energy in the world [J]: the ODE chassis, and in Crush the shell's points
  /// (the chassis's motion at each point plus the point's own relative velocity).
  double carKineticEnergy(const DeformableCar& dc) const;

  /// One car's step in three parts (crush_coupling.cpp): what it touches becomes the body's inputs
  /// (reads the world only), the body steps (touches nothing but the car), the reaction goes to ODE and
  /// the collision hull follows the dent (writes the world).
  void prepareCar(DeformableCar& dc) const;
  /// Refinement (DeformationSettings::refine), after prepareCar: splits the body's surface where this
  /// step's obstacles ask for it and moves the body onto the finer surface (refine_car.cpp).
  void refineCar(DeformableCar& dc) const;
  /// The body as `splits` (SurfaceHierarchy::splitOrder) make it from the car's build, with these point
  /// masses: its settings and the hierarchy (none for no split), at rest, for a restored state.
  void rebuildRefined(DeformableCar& dc, const std::vector<uint32_t>& splits,
                      const std::vector<double>& point_mass_kg) const;
  /// Work every force but the body's took from the chassis over ODE's step (the energy account) [J].
  double otherWork_J(const DeformableCar& dc, const Eigen::Vector3d& velocity_before,
                     const Eigen::Vector3d& omega_before) const;
  void solveCar(DeformableCar& dc) const;
  void finishCar(DeformableCar& dc);
  /// Visual: the ghost over ODE's step, before any car is prepared (DeformableCar::ghost_velocity_mps),
  /// and after the body's step.
  void advanceGhost(DeformableCar& dc) const;
  /// `impulse_Ns` (vehicle frame) less its vertical part, which the ground takes from a ghost.
  Eigen::Vector3d onTheGround(const DeformableCar& dc, const Eigen::Vector3d& impulse_Ns) const;
  void updateGhost(DeformableCar& dc) const;
  /// The deformable car `e` is, when it is one in the visual coupling; else null.
  const DeformableCar* visualCar(EntityRef e) const;
  /// Whether `other` is a deformable car stepped with `dc` as one group (both in the same coupling).
  bool pairsWith(const DeformableCar& dc, EntityRef other) const;
  /// Steps the bodies of `group` (indices into cars, prepared) as one: deform::stepGroup with a link for
  /// every pair of partners among them (car_group.cpp).
  void solveGroup(const std::vector<std::size_t>& group);
  /// Adds to dc.touching what its control points can reach within this step (crush_coupling.cpp).
  void addApproaching(DeformableCar& dc) const;
  static constexpr double kApproachMargin_m = 0.01;
  /// One car's coupling and metrics bookkeeping, and its body's state (simulation_state.cpp).
  void saveCar(StateWriter& out, const DeformableCar& dc) const;
  void restoreCar(StateReader& in, DeformableCar& dc);
  void updateMetrics(DeformableCar& dc, const Eigen::Vector3d& position_before,
                     const Eigen::Vector3d& velocity_before, double kinetic_before);
};

}  // namespace vehicle
