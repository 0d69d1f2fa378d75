#pragma once
// The ODE world (double precision) with its cars and obstacles, stepped at a fixed physics rate.
// Deterministic: the same calls give bit-identical states (stateHash), whatever else the process did
// (ODE's solver shuffles with a global seed; each World keeps its own). Worlds may live side by side
// but must step on one thread at a time (that seed and ODE's per-thread collision data).
#include <vehicle/car.hpp>
#include <vehicle/obstacle_shape.hpp>
#include <vehicle/pose.hpp>
#include <vehicle/state_io.hpp>
#include <vehicle/vehicle_settings.hpp>

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/mesh.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

namespace vehicle {

struct WorldSettings {
  /// Fixed steps per second (240-2000 typical; 50 .. 20,000 accepted) [Hz]. Below 120 Hz the crush is
  /// rate-dependent: a 60 Hz step crushes the 56 km/h wall crash 0.61 m against 0.40 m at 120 Hz and
  /// 0.38 m at 500 Hz, energy balanced (docs/STABILITY.md); step a slower game tick as several steps.
  double physics_rate_hz = 500;
  Eigen::Vector3d gravity_mps2{0, 0, -9.81};  ///< [m/s^2]
  int solver_iterations = 20;                 ///< ODE quick-step iterations per step [-]
  double contact_erp = 0.2;                   ///< share of a contact's penetration corrected per step [-]
  double contact_cfm = 1e-6;                  ///< contact constraint force mixing (softness) [m/N per step]
  int max_contacts_per_pair = 8;              ///< contact points kept per touching geom pair [-]
  bool ground = true;                         ///< add a ground plane at z = 0 (obstacle 0)
  double ground_friction = 1.0;  ///< its friction for bodies sliding on it (tyres use their own mu) [-]
};

using CarId = uint32_t;
using ObstacleId = uint32_t;

enum class ObstacleKind : uint8_t {
  Ground,      ///< a plane (HalfSpace)
  Wall,        ///< a static box
  Post,        ///< a static vertical cylinder or capsule
  Vegetation,  ///< a thin, light, free cylinder standing on its end: knocked over when hit
  Ramp,        ///< a static wedge, rising along its local +X
  ConvexMesh,  ///< the convex hull of a mesh (e.g. a jersey barrier), static or free
};

/// Whether an obstacle of this kind crushes a car's deformable body (its soft hull detects it, deform
/// dents the body against it, the backstop core is rigid against it): anything but the ground and ramps
/// (the visual coupling leaves vegetation to its rigid hull: vehicle/src/simulation.cpp, crushable).
/// A free one (a box, a tree) is a particle inside deform's substeps, pushed by its mass
/// (deform::StepInputs::contact_inverse_mass_per_kg). Other cars always do. The one definition the world
/// and the crush coupling share.
inline bool crushesBody(ObstacleKind kind) {
  return kind != ObstacleKind::Ground && kind != ObstacleKind::Ramp;
}

enum class PostShape : uint8_t { Cylinder, Capsule };

/// A car or an obstacle.
struct EntityRef {
  enum class Kind : uint8_t { Car, Obstacle } kind = Kind::Obstacle;
  uint32_t index = 0;
  bool operator==(const EntityRef&) const = default;
};

/// One contact point of the last step (ODE's convention: moving `a` along `normal` by depth_m
/// separates the two).
struct ContactPoint {
  EntityRef a, b;
  Eigen::Vector3d position_m{0, 0, 0};  ///< world [m]
  Eigen::Vector3d normal{0, 0, 1};      ///< unit, world, pointing from b into a
  double depth_m = 0;                   ///< penetration [m]
  /// Force the contact applied to `a` during the step (on `b`: its opposite; static obstacles take
  /// none); times the step it is the contact impulse [N].
  Eigen::Vector3d force_on_a_N{0, 0, 0};
  /// ODE made a rigid contact of it; false for a crush contact within the allowance (no force).
  bool rigid = true;
};

/// A contact seen from one car, in its vehicle frame (what the deformation side takes each step).
struct CarContact {
  EntityRef other;                       ///< what the car touches
  Eigen::Vector3d point_m{0, 0, 0};      ///< contact point, vehicle frame [m]
  Eigen::Vector3d normal{0, 0, 1};       ///< unit, vehicle frame, out of `other` into the car
  double depth_m = 0;                    ///< penetration [m]
  Eigen::Vector3d impulse_N_s{0, 0, 0};  ///< impulse on the car during the step, vehicle frame [N s]
};

/// Where a car starts.
struct CarStart {
  /// With on_ground: the ground point under the vehicle frame's origin (the car is lifted so its tyres
  /// touch at design ride height). Without: the vehicle frame's origin itself [m].
  Eigen::Vector3d position_m{0, 0, 0};
  double heading_rad = 0;  ///< about the world Z axis; 0 faces +X [rad]
  double speed_mps = 0;    ///< initial forward speed, wheels rolling with it [m/s]
  bool on_ground = true;
};

/// The chassis's rigid collision hull: `points`' convex hull at `count` points
/// (VehicleSettings::collision_points), the one definition every car and scene builds it by.
deform::ControlMesh collisionHull(const std::vector<Eigen::Vector3d>& points, std::size_t count,
                                  const char* source);

/// Where the last World::step's time went [ms].
struct WorldTimings {
  double tyres_ms = 0;    ///< every car's wheel raycasts, suspension and tyre forces [ms]
  double collide_ms = 0;  ///< ODE's collision detection (the contacts) [ms]
  double solve_ms = 0;    ///< ODE's quick step and its bookkeeping [ms]
};

class World {
 public:
  /// Throws deform::InputError naming the field for a rate or iteration count out of range.
  explicit World(const WorldSettings& settings = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const WorldSettings& settings() const;

  /// A car whose chassis is `model`'s body: collision hull collisionHull(vertices,
  /// settings.collision_points), mass settings.mass_kg over the solid hull; wheels from settings, the
  /// model's wheels or its bounding box (wheelsFromModel).
  CarId addCar(const deform::VehicleModel& model, const VehicleSettings& settings = {},
               const CarStart& start = {});
  /// A car with the given collision hull (vehicle frame); wheels from settings or the hull's bounding box.
  CarId addCar(const deform::ControlMesh& hull, const VehicleSettings& settings = {},
               const CarStart& start = {});
  /// A car with a collision hull built beforehand (vehicle frame, e.g. a shared CarBuild's) and its wheels
  /// (e.g. wheelsFromModel's): addCar(model, ...) without building the hull again.
  CarId addCar(const deform::ControlMesh& hull, std::vector<WheelSettings> wheels,
               const VehicleSettings& settings, const CarStart& start = {});
  /// A car whose chassis is a box of settings.box_size_m (no mesh needed).
  CarId addBoxCar(const VehicleSettings& settings = {}, const CarStart& start = {});

  std::size_t carCount() const;
  Car& car(CarId id);
  const Car& car(CarId id) const;

  /// A plane at height_m (normal +Z). Sizes and frictions below must be finite and positive, else
  /// deform::InputError naming the field.
  ObstacleId addGround(double height_m = 0, double friction = 1.0);
  /// A static box of `size_m` centred at `pose`.
  ObstacleId addWall(const Pose& pose, const Eigen::Vector3d& size_m, double friction = 0.6);
  /// A static vertical post standing on `base_m` (capsule: height includes the caps).
  ObstacleId addPost(const Eigen::Vector3d& base_m, double radius_m, double height_m,
                     PostShape shape = PostShape::Cylinder, double friction = 0.6);
  /// A free upright cylinder (a small tree, a bush, a sign) standing on `base_m`.
  ObstacleId addVegetation(const Eigen::Vector3d& base_m, double radius_m, double height_m, double mass_kg,
                           double friction = 0.8);
  /// A static wedge: `foot` is the middle of its low edge on the ground, it rises along the foot's +X
  /// to height_m at length_m; width_m across.
  ObstacleId addRamp(const Pose& foot, double length_m, double width_m, double height_m,
                     double friction = 1.0);
  /// The convex hull of `mesh` (vehicle-frame coordinates of e.g. loadVehicleModel's body) placed at
  /// `pose`; mass_kg 0 is static, else a free body of uniform density.
  ObstacleId addConvexMesh(const deform::Mesh& mesh, const Pose& pose, double mass_kg = 0,
                           double friction = 0.6);

  std::size_t obstacleCount() const;
  ObstacleKind obstacleKind(ObstacleId id) const;
  bool obstacleIsDynamic(ObstacleId id) const;
  /// Pose of the obstacle's own frame (its shape's local coordinates) now.
  Pose obstaclePose(ObstacleId id) const;
  /// The velocity of the obstacle's material at the world point `point_m`, and its angular velocity
  /// (world): zero for a static obstacle or the ground [m/s], [rad/s].
  Eigen::Vector3d obstacleVelocity_mps(ObstacleId id, const Eigen::Vector3d& point_m) const;
  Eigen::Vector3d obstacleAngularVelocity_radps(ObstacleId id) const;
  /// The obstacle's shape in the world now (for the crush coupling: transformShape it into a car's
  /// vehicle frame, query supportPoint or pointPenetration).
  ObstacleShape obstacleShape(ObstacleId id) const;
  /// Obstacle or car shape in the world.
  ObstacleShape shapeOf(EntityRef entity) const;

  /// Crush coupling (simulation.hpp): car `id`'s hull no longer resists anything but the ground and
  /// ramps (its contacts are still listed by contacts(), with rigid false and no force: the deformable
  /// body resists them); a backstop core, the hull shrunk by `allowance_m` towards the centre of mass, is
  /// rigid against them (and against other cars' cores), so no car intrudes further than its stroke.
  /// 0 (the default) keeps the car rigid. Call again after Car::setCollisionHull. Throws
  /// deform::InputError for a negative or non-finite allowance.
  void setCrushAllowance(CarId id, double allowance_m);
  double crushAllowance(CarId id) const;
  /// Crush coupling, as setCrushAllowance but with the backstop given as the car's rigid parts: boxes in
  /// the vehicle frame [m] (a passenger cell, an engine block), rigid against what the hull meets once
  /// it reaches them. No boxes keeps the car rigid. Throws deform::InputError for a box with a non-finite
  /// corner or its lower corner above its upper one.
  void setRigidParts(CarId id, const std::vector<deform::Aabb>& boxes_m);
  /// Whether car `id` is in the crush coupling (its hull soft, a backstop rigid).
  bool crushes(CarId id) const;
  /// A force on a car's chassis or a free obstacle at a world point, for the next step only (static
  /// obstacles and the ground ignore it) [N], [m]. Wakes a sleeping obstacle. Throws deform::InputError for
  /// a non-finite force or point (ODE would abort).
  void addForce(EntityRef entity, const Eigen::Vector3d& force_N, const Eigen::Vector3d& point_m);

  /// An impulse on a car's chassis or a free obstacle, now: its velocity changes by impulse / mass and its
  /// angular velocity by I^-1 ((point - centre of mass) x impulse + angular_impulse) (world) [N s], [m],
  /// [N m s]. Static obstacles and the ground ignore it. Wakes a sleeping obstacle. Throws
  /// deform::InputError for a non-finite argument.
  void applyImpulse(EntityRef entity, const Eigen::Vector3d& impulse_Ns, const Eigen::Vector3d& point_m,
                    const Eigen::Vector3d& angular_impulse_Nms = Eigen::Vector3d::Zero());
  /// Moves a car's chassis by `shift_m` (world) [m], keeping its velocity and orientation.
  void shiftCar(CarId id, const Eigen::Vector3d& shift_m);
  /// Moves a car's chassis or a free obstacle by `shift_m` (world) [m], keeping its velocity and
  /// orientation; static obstacles and the ground stay. Wakes a sleeping obstacle.
  void shift(EntityRef entity, const Eigen::Vector3d& shift_m);
  /// 1 / mass of a car's chassis or a free obstacle [1/kg]; 0 for static obstacles and the ground.
  double inverseMass_per_kg(EntityRef entity) const;
  /// A free obstacle's kinetic energy, translation and turn [J]; 0 for a static one.
  double obstacleKineticEnergy_J(ObstacleId id) const;

  /// One fixed step of 1 / physics_rate_hz: wheel forces of every car, collisions, ODE quick step.
  void step();
  /// As many fixed steps as fit into the time accumulated so far plus dt_s; returns how many. Throws
  /// deform::InputError naming "dt_s" for zero, negative or non-finite dt_s.
  int advance(double dt_s);
  double fixedDt_s() const;
  double time_s() const;
  uint64_t stepCount() const;

  /// Where the last step's time went.
  WorldTimings lastTimings() const;

  /// Contacts between bodies (chassis, obstacles) found in the last step.
  const std::vector<ContactPoint>& contacts() const;

  /// The last step's contacts of car `id`, turned into its vehicle frame at the pose it has now.
  std::vector<CarContact> carContacts(CarId id) const;

  /// Everything that decides the world's future, bit for bit: time, step count, fixed-step accumulator,
  /// ODE's shuffle seed; every car's chassis motion, steering, input, wheels, collision hull and crush
  /// backstop; every free obstacle's motion and sleep countdown; whether each body is asleep; the order of
  /// the collision space's geoms (it orders the contacts). Taken between steps (the last step's contacts
  /// are not kept: the next step finds its own).
  void saveState(StateWriter& out) const;
  /// Puts back what saveState wrote into a world built the same way (same cars, obstacles, settings).
  /// Throws deform::InputError (through `in`) for bytes that do not fit it.
  void restoreState(StateReader& in);

  /// FNV-1a (64 bit) over saveState's bytes less the obstacle count and where static geoms sit in the
  /// collision order (StateWriter::forHash): obstacles that never take part change no hash.
  uint64_t stateHash() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Messages (warnings) ODE printed since the program started; tests expect none.
std::size_t engineMessageCount();

/// FNV-1a 64-bit hash of raw bytes, continuing from `hash`.
uint64_t fnv1a(const void* data, std::size_t bytes, uint64_t hash = 14695981039346656037ull);

}  // namespace vehicle
