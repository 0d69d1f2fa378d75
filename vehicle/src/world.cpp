// The ODE world: cars, obstacles, collisions and the fixed-rate step.
#include <vehicle/mass_properties.hpp>
#include <vehicle/world.hpp>

#include "input_checks.hpp"
#include "ode_support.hpp"

#include <deform/contact_shapes.hpp>
#include <deform/error.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <string>

namespace vehicle {
namespace {

std::atomic<std::size_t> g_engine_messages{0};

void countingMessageHandler(int errnum, const char* msg, va_list ap) {
  ++g_engine_messages;
  std::fprintf(stderr, "ODE message %d: ", errnum);
  std::vfprintf(stderr, msg, ap);
  std::fprintf(stderr, "\n");
}

void installHandlers() {
  static std::once_flag once;
  std::call_once(once, [] { dSetMessageHandler(countingMessageHandler); });
}

constexpr uint32_t kCarKind = 0, kObstacleKind = 1;
constexpr uint32_t kCarCoreKind = 2;  ///< a car's crush backstop geom

/// The 12 triangles of an axis-aligned box centred at `centre_m`, outward.
deform::ControlMesh boxHull(const Eigen::Vector3d& size_m, const Eigen::Vector3d& centre_m) {
  deform::ControlMesh hull;
  for (int i = 0; i < 8; ++i)
    hull.points_m.push_back(centre_m + 0.5 * Eigen::Vector3d((i & 1) ? size_m.x() : -size_m.x(),
                                                             (i & 2) ? size_m.y() : -size_m.y(),
                                                             (i & 4) ? size_m.z() : -size_m.z()));
  // Corner index bits: x = 1, y = 2, z = 4. Faces counter-clockwise seen from outside.
  const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    hull.triangles.push_back({f[0], f[1], f[2]});
    hull.triangles.push_back({f[0], f[2], f[3]});
  }
  return hull;
}

}  // namespace

uint64_t fnv1a(const void* data, std::size_t bytes, uint64_t hash) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    hash ^= p[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

std::size_t engineMessageCount() {
  return g_engine_messages.load();
}

struct ObstacleEntry {
  ObstacleKind kind = ObstacleKind::Wall;
  dGeomID geom = nullptr;
  dBodyID body = nullptr;
  ObstacleShape local;                      ///< shape in the geom's frame (world for the ground)
  std::unique_ptr<ode::ConvexData> convex;  ///< what a convex geom points into
  double friction = 0.6;
  int still_steps = 0;  ///< a free body: steps in a row it has rested on something (its sleep countdown)
};

struct World::Impl {
  WorldSettings settings;
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  ode::GeomGrid geom_grid;  ///< the space's geoms by place, rebuilt every step (rays, collision pairs)
  std::vector<uint64_t> pair_scratch;
  dJointGroupID contact_joints = nullptr;
  std::vector<std::unique_ptr<Car>> cars;
  std::vector<ObstacleEntry> obstacles;
  std::vector<double> crush_allowance_m;  ///< per car (setCrushAllowance) [m]
  std::vector<char>
      crush_coupled;  ///< per car: hull soft, backstop rigid (setCrushAllowance / setRigidParts)
  std::vector<ContactPoint> contacts;
  std::deque<dJointFeedback> feedback;  ///< one per contact; a deque so ODE's pointers stay valid
  std::vector<double> feedback_sign;    ///< -1 where ODE's body 1 is b (a is static): f1 acts on b
  std::vector<dContact> scratch;
  unsigned long random_seed = 0;  ///< ODE's quick-step shuffle seed, owned by this world
  double time_s = 0, accumulator_s = 0;
  uint64_t steps = 0;
  WorldTimings timings;  ///< of the last step

  /// Free obstacles sleep after kSleepDelay_s resting on something (they have contact joints) below
  /// kSleepSpeed_mps and kSleepSpin_rad_s (DESIGN.md section 8: no work for what does not move; a
  /// standing tree does not creep). A contact with a moving body, a wheel standing on them, addForce or
  /// applyImpulse wakes them. Called after ODE's step, while its contact joints are still attached.
  void sleepRestingObstacles() {
    constexpr double kSleepDelay_s = 0.5, kSleepSpeed_mps = 0.01, kSleepSpin_rad_s = 0.01;
    const int delay_steps = static_cast<int>(std::ceil(kSleepDelay_s * settings.physics_rate_hz));
    for (ObstacleEntry& o : obstacles) {
      if (o.body == nullptr) continue;
      if (!dBodyIsEnabled(o.body)) {
        o.still_steps = 0;
        continue;
      }
      const bool still = dBodyGetNumJoints(o.body) > 0 &&
                         ode::vec(dBodyGetLinearVel(o.body)).norm() <= kSleepSpeed_mps &&
                         ode::vec(dBodyGetAngularVel(o.body)).norm() <= kSleepSpin_rad_s;
      o.still_steps = still ? o.still_steps + 1 : 0;
      if (o.still_steps >= delay_steps) {
        dBodyDisable(o.body);
        dBodySetLinearVel(o.body, 0, 0, 0);
        dBodySetAngularVel(o.body, 0, 0, 0);
        o.still_steps = 0;
      }
    }
  }

  /// Every geom in the space in a fixed order (cars' hulls and backstops, then obstacles): what the
  /// saved geom order refers to.
  std::vector<dGeomID> geoms() const {
    std::vector<dGeomID> out;
    for (const auto& c : cars) c->appendGeoms(out);
    for (const auto& o : obstacles) out.push_back(o.geom);
    return out;
  }

  double frictionOf(dGeomID geom) const {
    uint32_t kind = 0, index = 0;
    if (!ode::unpackEntity(dGeomGetData(geom), kind, index)) return 0.6;
    return kind == kObstacleKind ? obstacles[index].friction : cars[index]->settings().body_friction;
  }
  static EntityRef entityOf(dGeomID geom) {
    uint32_t kind = 0, index = 0;
    ode::unpackEntity(dGeomGetData(geom), kind, index);
    return {kind == kObstacleKind ? EntityRef::Kind::Obstacle : EntityRef::Kind::Car, index};
  }

  static void nearCallback(void* data, dGeomID g1, dGeomID g2) {
    auto* self = static_cast<Impl*>(data);
    dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
    if (b1 == nullptr && b2 == nullptr) return;
    if (b1 == b2) return;
    // Crush (setCrushAllowance): a car's hull only detects what it crushes into (the deformable body
    // resists it); its backstop core is rigid against it. Cores ignore the ground, ramps and soft hulls.
    const GeomRole r1 = self->roleOf(g1), r2 = self->roleOf(g2);
    const bool crushable = self->crushable(g1) && self->crushable(g2);
    if ((r1 == GeomRole::Core || r2 == GeomRole::Core) &&
        (!crushable || r1 == GeomRole::SoftHull || r2 == GeomRole::SoftHull))
      return;
    const bool soft = crushable && (r1 == GeomRole::SoftHull || r2 == GeomRole::SoftHull);
    const int found =
        dCollide(g1, g2, static_cast<int>(self->scratch.size()), &self->scratch[0].geom, sizeof(dContact));
    const double mu = std::sqrt(self->frictionOf(g1) * self->frictionOf(g2));
    for (int i = 0; i < found; ++i) {
      dContact& c = self->scratch[static_cast<std::size_t>(i)];
      if (soft) {
        self->feedback.emplace_back();
        self->feedback_sign.push_back(0.0);
        self->contacts.push_back({entityOf(g1), entityOf(g2), ode::vec(c.geom.pos), ode::vec(c.geom.normal),
                                  c.geom.depth, Eigen::Vector3d::Zero(), false});
        continue;
      }
      c.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
      c.surface.mu = mu;
      // A crush backstop corrects its overlap gently: the crushed structure in front of it does not
      // spring back, so a stiff push-out would throw the car back. So does a free obstacle against a static
      // thing (a box against a wall or the ground): a car's body may have pushed it in within the step
      // before this contact existed (deform holds it only by the contacts it is told of), and pushed out at
      // up to the correcting velocity it was thrown back at the car (a 1000 kg box pinched against a wall
      // at 30 km/h: +12.7 % of the impact energy unexplained; +10.1 % with only the wall's contact gentle,
      // +3.8 % with the ground's too, where the car that rode onto the box pushed it down).
      const bool core = r1 == GeomRole::Core || r2 == GeomRole::Core;
      // A crush backstop meets a post across its axis only, as the body does (deform's
      // CylinderShape::across_only): at the rim of a low post a normal half up its axis turned a sedan's
      // motion at 250 km/h up it as a ramp would (a post of 0.3 m radius and height: 9.3 m up).
      Eigen::Vector3d around{0, 0, 0};  // a post's tangent across its axis: its friction's only direction
      if (core && !self->acrossPost(g1, g2, c.geom, around)) continue;
      if (around.squaredNorm() > 0) {
        c.surface.mode |= dContactMu2 | dContactFDir1;
        c.surface.mu2 = 0;
        for (int k = 0; k < 3; ++k) c.fdir1[k] = around[k];
      }
      const bool gentle = core || self->freeAgainstStatic(g1, g2);
      c.surface.soft_erp = gentle ? 0.1 * self->settings.contact_erp : self->settings.contact_erp;
      c.surface.soft_cfm = self->settings.contact_cfm;
      dJointID joint = dJointCreateContact(self->world, self->contact_joints, &c);
      dJointAttach(joint, b1, b2);
      self->feedback.emplace_back();
      self->feedback_sign.push_back(b1 == nullptr ? -1.0 : 1.0);
      dJointSetFeedback(joint, &self->feedback.back());
      self->contacts.push_back({entityOf(g1), entityOf(g2), ode::vec(c.geom.pos), ode::vec(c.geom.normal),
                                c.geom.depth, Eigen::Vector3d::Zero(), true});
    }
  }

  /// A contact with a post keeps only its normal's part across the post's axis (false: within 30 degrees
  /// of the axis, no contact), and `around` becomes the tangent across the axis, the one direction its
  /// friction may act in (none along the axis: the vertical friction of a core stopped at a low post
  /// lifted the car as its nose dipped). Any other contact is left as it is.
  bool acrossPost(dGeomID g1, dGeomID g2, dContactGeom& contact, Eigen::Vector3d& around) const {
    for (const dGeomID g : {g1, g2}) {
      uint32_t kind = 0, index = 0;
      if (!ode::unpackEntity(dGeomGetData(g), kind, index) || kind != kObstacleKind) continue;
      if (obstacles[index].kind != ObstacleKind::Post) continue;
      const int cls = dGeomGetClass(g);
      if (cls != dCylinderClass && cls != dCapsuleClass) continue;
      const dReal* r = dGeomGetRotation(g);  // 3x4, row-major: the local z axis is its third column
      const Eigen::Vector3d axis(r[2], r[6], r[10]);
      Eigen::Vector3d unit;
      if (!deform::acrossAxis(ode::vec(contact.normal), axis, unit)) return false;
      for (int k = 0; k < 3; ++k) contact.normal[k] = unit[k];
      around = axis.cross(unit).normalized();
    }
    return true;
  }

  /// A free obstacle (an obstacle with an ODE body) against a static obstacle or the ground.
  static bool freeAgainstStatic(dGeomID g1, dGeomID g2) {
    const dGeomID moving = dGeomGetBody(g1) != nullptr ? g1 : g2, fixed = moving == g1 ? g2 : g1;
    if (dGeomGetBody(fixed) != nullptr) return false;
    uint32_t kind = 0, index = 0, fixed_kind = 0, fixed_index = 0;
    return ode::unpackEntity(dGeomGetData(moving), kind, index) && kind == kObstacleKind &&
           ode::unpackEntity(dGeomGetData(fixed), fixed_kind, fixed_index) && fixed_kind == kObstacleKind;
  }

  enum class GeomRole { Plain, SoftHull, Core };
  GeomRole roleOf(dGeomID geom) const {
    uint32_t kind = 0, index = 0;
    if (!ode::unpackEntity(dGeomGetData(geom), kind, index)) return GeomRole::Plain;
    if (kind == kCarCoreKind) return GeomRole::Core;
    if (kind == kCarKind && crush_coupled[index]) return GeomRole::SoftHull;
    return GeomRole::Plain;
  }
  /// crushesBody (world.hpp); a car always.
  bool crushable(dGeomID geom) const {
    const EntityRef e = entityOf(geom);
    return e.kind == EntityRef::Kind::Car || crushesBody(obstacles[e.index].kind);
  }

  /// A car's chassis or an obstacle's ODE body (null for a static obstacle and the ground).
  dBodyID bodyOf(EntityRef entity) const {
    return entity.kind == EntityRef::Kind::Car ? cars.at(entity.index)->body_
                                               : obstacles.at(entity.index).body;
  }

  ObstacleId addObstacle(ObstacleEntry entry) {
    const auto id = static_cast<ObstacleId>(obstacles.size());
    dGeomSetData(entry.geom, ode::packEntity(kObstacleKind, id));
    obstacles.push_back(std::move(entry));
    return id;
  }

  /// A convex geom (static, or on a new body of `mass_kg`) for a hull given in a frame at `pose`.
  ObstacleId addConvex(ObstacleKind kind, const deform::ControlMesh& hull, const Pose& pose, double mass_kg,
                       double friction) {
    const SolidProperties solid = solidProperties(hull.points_m, hull.triangles, "obstacle hull");
    ObstacleEntry entry;
    entry.kind = kind;
    entry.friction = friction;
    entry.local.type = ShapeType::Convex;
    for (const auto& p : hull.points_m) entry.local.vertices_m.push_back(p - solid.centroid_m);
    entry.local.centre_m.setZero();
    entry.convex =
        std::make_unique<ode::ConvexData>(ode::makeConvexData(entry.local.vertices_m, hull.triangles));
    const ode::ConvexData& d = *entry.convex;
    entry.geom = dCreateConvex(space, d.planes.data(), d.face_count, d.points.data(), d.point_count,
                               d.polygons.data());
    const Pose placed{pose.toWorld(solid.centroid_m), pose.orientation};
    if (mass_kg > 0) {
      entry.body = dBodyCreate(world);
      dMass mass;
      dMassSetZero(&mass);
      mass.mass = mass_kg;
      const Eigen::Matrix3d inertia = mass_kg * solid.inertia_per_kg;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) mass.I[4 * r + c] = inertia(r, c);
      dBodySetMass(entry.body, &mass);
      dGeomSetBody(entry.geom, entry.body);
      ode::setBodyPose(entry.body, placed);
    } else {
      ode::setGeomPose(entry.geom, placed);
    }
    return addObstacle(std::move(entry));
  }

  CarId addCar(const deform::ControlMesh& hull, const VehicleSettings& car_settings,
               std::vector<WheelSettings> wheels, const CarStart& start) {
    VehicleSettings resolved = car_settings;  // check the wheels actually used (model or bounding box too)
    resolved.wheels = wheels;
    checkVehicleSettings(resolved);
    if (wheels.size() < 3)
      throw deform::InputError("vehicle: wheels: a car needs at least 3 (got " +
                               std::to_string(wheels.size()) + ")");
    detail::requireFinite(start.position_m, "start.position_m");
    if (!std::isfinite(start.heading_rad)) throw deform::InputError("start.heading_rad: must be finite");
    if (!std::isfinite(start.speed_mps)) throw deform::InputError("start.speed_mps: must be finite");
    Eigen::Vector3d origin = start.position_m;
    if (start.on_ground) {
      double lowest = 1e300;
      for (const auto& w : wheels) lowest = std::min(lowest, w.centre_m.z() - w.radius_m);
      origin.z() -= lowest;
    }
    const Pose pose = Pose::yawed(origin, start.heading_rad);
    const Eigen::Vector3d velocity = start.speed_mps * (pose.orientation * Eigen::Vector3d::UnitX());
    const auto id = static_cast<CarId>(cars.size());
    cars.push_back(std::unique_ptr<Car>(new Car(world, space, ode::packEntity(kCarKind, id), hull,
                                                car_settings, std::move(wheels), pose, velocity)));
    crush_allowance_m.push_back(0.0);
    crush_coupled.push_back(0);
    return id;
  }
};

World::World(const WorldSettings& settings) : impl_(std::make_unique<Impl>()) {
  if (!(std::isfinite(settings.physics_rate_hz) && settings.physics_rate_hz >= 50 &&
        settings.physics_rate_hz <= 20000))
    throw deform::InputError(
        detail::fieldMessage("physics_rate_hz", "must be between 50 and 20000", settings.physics_rate_hz));
  if (settings.solver_iterations < 1 || settings.solver_iterations > 1000)
    throw deform::InputError(
        detail::fieldMessage("solver_iterations", "must be between 1 and 1000", settings.solver_iterations));
  detail::requireFinite(settings.gravity_mps2, "gravity_mps2");
  detail::requirePositive(settings.contact_erp, "contact_erp");
  detail::requireNonNegative(settings.contact_cfm, "contact_cfm");
  if (settings.max_contacts_per_pair < 1 || settings.max_contacts_per_pair > 64)
    throw deform::InputError(detail::fieldMessage("max_contacts_per_pair", "must be between 1 and 64",
                                                  settings.max_contacts_per_pair));
  installHandlers();
  dInitODE2(0);
  dAllocateODEDataForThread(dAllocateMaskAll);
  Impl& m = *impl_;
  m.settings = settings;
  m.world = dWorldCreate();
  m.space = dSimpleSpaceCreate(nullptr);  // pairs in insertion order: deterministic
  m.contact_joints = dJointGroupCreate(0);
  m.scratch.resize(static_cast<std::size_t>(settings.max_contacts_per_pair));
  dWorldSetGravity(m.world, settings.gravity_mps2.x(), settings.gravity_mps2.y(), settings.gravity_mps2.z());
  dWorldSetERP(m.world, settings.contact_erp);
  dWorldSetCFM(m.world, settings.contact_cfm);
  dWorldSetQuickStepNumIterations(m.world, settings.solver_iterations);
  dWorldSetContactSurfaceLayer(m.world, 0.001);
  dWorldSetContactMaxCorrectingVel(m.world, 5.0);
  // Free obstacles (not cars) sleep after half a second at rest on something (World::step's own
  // countdown, not ODE's auto-disable, whose countdown ODE neither shows nor takes back, so a saved
  // state could not hold it).
  dWorldSetAutoDisableFlag(m.world, 0);
  if (settings.ground) addGround(0.0, settings.ground_friction);
}

World::~World() {
  Impl& m = *impl_;
  m.cars.clear();
  for (auto& o : m.obstacles) {
    dGeomDestroy(o.geom);
    if (o.body) dBodyDestroy(o.body);
  }
  m.obstacles.clear();
  dJointGroupDestroy(m.contact_joints);
  dSpaceDestroy(m.space);
  dWorldDestroy(m.world);
  dCloseODE();
}

const WorldSettings& World::settings() const {
  return impl_->settings;
}

deform::ControlMesh collisionHull(const std::vector<Eigen::Vector3d>& points, std::size_t count,
                                  const char* source) {
  return deform::buildControlMesh(points, count, source);
}

CarId World::addCar(const deform::VehicleModel& model, const VehicleSettings& settings,
                    const CarStart& start) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(model.body.positions_m.size());
  for (const auto& p : model.body.positions_m) points.push_back(p.cast<double>());
  const std::string source = model.source.empty() ? "vehicle model" : model.source;
  const deform::ControlMesh hull = collisionHull(points, settings.collision_points, source.c_str());
  return impl_->addCar(hull, settings, wheelsFromModel(settings, model), start);
}

CarId World::addCar(const deform::ControlMesh& hull, std::vector<WheelSettings> wheels,
                    const VehicleSettings& settings, const CarStart& start) {
  return impl_->addCar(hull, settings, std::move(wheels), start);
}

CarId World::addCar(const deform::ControlMesh& hull, const VehicleSettings& settings, const CarStart& start) {
  std::vector<WheelSettings> wheels = settings.wheels;
  if (wheels.empty()) {
    deform::Aabb box{hull.points_m.front(), hull.points_m.front()};
    for (const auto& p : hull.points_m) {
      box.min_m = box.min_m.cwiseMin(p);
      box.max_m = box.max_m.cwiseMax(p);
    }
    wheels = wheelsFromBoundingBox(box);
  }
  if (hull.points_m.size() < 4) throw deform::InputError("vehicle hull: needs at least 4 points");
  return impl_->addCar(hull, settings, std::move(wheels), start);
}

CarId World::addBoxCar(const VehicleSettings& settings, const CarStart& start) {
  checkVehicleSettings(settings);
  const Eigen::Vector3d size = settings.box_size_m;
  return addCar(boxHull(size, Eigen::Vector3d(0, 0, 0.5 * size.z())), settings, start);
}

std::size_t World::carCount() const {
  return impl_->cars.size();
}
Car& World::car(CarId id) {
  return *impl_->cars.at(id);
}
const Car& World::car(CarId id) const {
  return *impl_->cars.at(id);
}

ObstacleId World::addGround(double height_m, double friction) {
  if (!std::isfinite(height_m)) throw deform::InputError("ground.height_m: must be finite");
  detail::requireNonNegative(friction, "ground.friction");
  ObstacleEntry entry;
  entry.kind = ObstacleKind::Ground;
  entry.friction = friction;
  entry.geom = dCreatePlane(impl_->space, 0, 0, 1, height_m);
  entry.local.type = ShapeType::HalfSpace;
  entry.local.normal = Eigen::Vector3d::UnitZ();
  entry.local.offset_m = height_m;
  return impl_->addObstacle(std::move(entry));
}

ObstacleId World::addWall(const Pose& pose, const Eigen::Vector3d& size_m, double friction) {
  detail::requireFinite(pose, "wall.pose");
  for (int i = 0; i < 3; ++i) detail::requirePositive(size_m[i], "wall.size_m");
  detail::requireNonNegative(friction, "wall.friction");
  ObstacleEntry entry;
  entry.kind = ObstacleKind::Wall;
  entry.friction = friction;
  entry.geom = dCreateBox(impl_->space, size_m.x(), size_m.y(), size_m.z());
  ode::setGeomPose(entry.geom, pose);
  entry.local.type = ShapeType::Box;
  entry.local.half_extents_m = 0.5 * size_m;
  return impl_->addObstacle(std::move(entry));
}

ObstacleId World::addPost(const Eigen::Vector3d& base_m, double radius_m, double height_m, PostShape shape,
                          double friction) {
  detail::requireFinite(base_m, "post.base_m");
  detail::requirePositive(radius_m, "post.radius_m");
  detail::requirePositive(height_m, "post.height_m");
  detail::requireNonNegative(friction, "post.friction");
  ObstacleEntry entry;
  entry.kind = ObstacleKind::Post;
  entry.friction = friction;
  entry.local.radius_m = radius_m;
  if (shape == PostShape::Capsule) {
    if (!(height_m > 2 * radius_m))
      throw deform::InputError("post.height_m: a capsule must be taller than its diameter");
    entry.geom = dCreateCapsule(impl_->space, radius_m, height_m - 2 * radius_m);
    entry.local.type = ShapeType::Capsule;
    entry.local.a_m = {0, 0, -(0.5 * height_m - radius_m)};
    entry.local.b_m = {0, 0, 0.5 * height_m - radius_m};
  } else {
    entry.geom = dCreateCylinder(impl_->space, radius_m, height_m);
    entry.local.type = ShapeType::Cylinder;
    entry.local.a_m = {0, 0, -0.5 * height_m};
    entry.local.b_m = {0, 0, 0.5 * height_m};
  }
  ode::setGeomPose(entry.geom,
                   {base_m + Eigen::Vector3d(0, 0, 0.5 * height_m), Eigen::Quaterniond::Identity()});
  return impl_->addObstacle(std::move(entry));
}

ObstacleId World::addVegetation(const Eigen::Vector3d& base_m, double radius_m, double height_m,
                                double mass_kg, double friction) {
  detail::requireFinite(base_m, "vegetation.base_m");
  detail::requirePositive(radius_m, "vegetation.radius_m");
  detail::requirePositive(height_m, "vegetation.height_m");
  detail::requirePositive(mass_kg, "vegetation.mass_kg");
  detail::requireNonNegative(friction, "vegetation.friction");
  ObstacleEntry entry;
  entry.kind = ObstacleKind::Vegetation;
  entry.friction = friction;
  entry.geom = dCreateCylinder(impl_->space, radius_m, height_m);
  entry.body = dBodyCreate(impl_->world);
  dMass mass;
  dMassSetCylinderTotal(&mass, mass_kg, 3, radius_m, height_m);
  dBodySetMass(entry.body, &mass);
  dGeomSetBody(entry.geom, entry.body);
  ode::setBodyPose(entry.body,
                   {base_m + Eigen::Vector3d(0, 0, 0.5 * height_m), Eigen::Quaterniond::Identity()});
  entry.local.type = ShapeType::Cylinder;
  entry.local.radius_m = radius_m;
  entry.local.a_m = {0, 0, -0.5 * height_m};
  entry.local.b_m = {0, 0, 0.5 * height_m};
  return impl_->addObstacle(std::move(entry));
}

ObstacleId World::addRamp(const Pose& foot, double length_m, double width_m, double height_m,
                          double friction) {
  detail::requireFinite(foot, "ramp.pose");
  detail::requirePositive(length_m, "ramp.length_m");
  detail::requirePositive(width_m, "ramp.width_m");
  detail::requirePositive(height_m, "ramp.height_m");
  detail::requireNonNegative(friction, "ramp.friction");
  deform::ControlMesh wedge;
  const double w = 0.5 * width_m;
  // Corners: 0/1 the low edge (left/right), 2/3 the far bottom edge, 4/5 the top edge above it.
  wedge.points_m = {{0, w, 0},
                    {0, -w, 0},
                    {length_m, w, 0},
                    {length_m, -w, 0},
                    {length_m, w, height_m},
                    {length_m, -w, height_m}};
  wedge.triangles = {{0, 2, 3}, {0, 3, 1},  // bottom (normal -Z)
                     {2, 4, 5}, {2, 5, 3},  // back (+X)
                     {0, 1, 5}, {0, 5, 4},  // slope
                     {0, 4, 2},             // left side (+Y)
                     {1, 3, 5}};            // right side (-Y)
  return impl_->addConvex(ObstacleKind::Ramp, wedge, foot, 0.0, friction);
}

ObstacleId World::addConvexMesh(const deform::Mesh& mesh, const Pose& pose, double mass_kg, double friction) {
  detail::requireFinite(pose, "convex_mesh.pose");
  detail::requireNonNegative(mass_kg, "convex_mesh.mass_kg");
  detail::requireNonNegative(friction, "convex_mesh.friction");
  deform::checkMesh(mesh, "convex_mesh");
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : mesh.positions_m) points.push_back(p.cast<double>());
  return impl_->addConvex(ObstacleKind::ConvexMesh, deform::convexHull(points, "convex_mesh"), pose, mass_kg,
                          friction);
}

std::size_t World::obstacleCount() const {
  return impl_->obstacles.size();
}
ObstacleKind World::obstacleKind(ObstacleId id) const {
  return impl_->obstacles.at(id).kind;
}
bool World::obstacleIsDynamic(ObstacleId id) const {
  return impl_->obstacles.at(id).body != nullptr;
}

Pose World::obstaclePose(ObstacleId id) const {
  const ObstacleEntry& o = impl_->obstacles.at(id);
  if (o.kind == ObstacleKind::Ground) return {};
  return ode::geomPose(o.geom);
}

Eigen::Vector3d World::obstacleVelocity_mps(ObstacleId id, const Eigen::Vector3d& point_m) const {
  const ObstacleEntry& o = impl_->obstacles.at(id);
  if (o.body == nullptr) return Eigen::Vector3d::Zero();
  return ode::vec(dBodyGetLinearVel(o.body)) +
         ode::vec(dBodyGetAngularVel(o.body)).cross(point_m - ode::vec(dBodyGetPosition(o.body)));
}

Eigen::Vector3d World::obstacleAngularVelocity_radps(ObstacleId id) const {
  const ObstacleEntry& o = impl_->obstacles.at(id);
  return o.body == nullptr ? Eigen::Vector3d::Zero() : ode::vec(dBodyGetAngularVel(o.body));
}

ObstacleShape World::obstacleShape(ObstacleId id) const {
  const ObstacleEntry& o = impl_->obstacles.at(id);
  if (o.kind == ObstacleKind::Ground) return o.local;
  return transformShape(o.local, obstaclePose(id).inverse());
}

ObstacleShape World::shapeOf(EntityRef entity) const {
  return entity.kind == EntityRef::Kind::Car ? car(entity.index).shape() : obstacleShape(entity.index);
}

void World::setCrushAllowance(CarId id, double allowance_m) {
  detail::requireNonNegative(allowance_m, "crush_allowance_m");
  impl_->crush_allowance_m.at(id) = allowance_m;
  impl_->crush_coupled.at(id) = allowance_m > 0;
  impl_->cars.at(id)->setCoreHull(allowance_m, ode::packEntity(kCarCoreKind, id));
}

void World::setRigidParts(CarId id, const std::vector<deform::Aabb>& boxes_m) {
  for (const deform::Aabb& box : boxes_m)
    if (!box.min_m.allFinite() || !box.max_m.allFinite() || !(box.min_m.array() <= box.max_m.array()).all())
      throw deform::InputError(
          "rigid_parts: a box needs finite corners, its lower corner below its upper one");
  impl_->crush_allowance_m.at(id) = 0;
  impl_->crush_coupled.at(id) = !boxes_m.empty();
  impl_->cars.at(id)->setCoreBoxes(boxes_m, ode::packEntity(kCarCoreKind, id));
}

bool World::crushes(CarId id) const {
  return impl_->crush_coupled.at(id) != 0;
}

double World::crushAllowance(CarId id) const {
  return impl_->crush_allowance_m.at(id);
}

void World::addForce(EntityRef entity, const Eigen::Vector3d& force_N, const Eigen::Vector3d& point_m) {
  if (!force_N.allFinite() || !point_m.allFinite())
    throw deform::InputError("addForce: the force and its point must be finite (ODE aborts on a NaN)");
  dBodyID body = impl_->bodyOf(entity);
  if (body == nullptr) return;
  dBodyEnable(body);
  dBodyAddForceAtPos(body, force_N.x(), force_N.y(), force_N.z(), point_m.x(), point_m.y(), point_m.z());
}

void World::applyImpulse(EntityRef entity, const Eigen::Vector3d& impulse_Ns, const Eigen::Vector3d& point_m,
                         const Eigen::Vector3d& angular_impulse_Nms) {
  if (!impulse_Ns.allFinite() || !point_m.allFinite() || !angular_impulse_Nms.allFinite())
    throw deform::InputError(
        "applyImpulse: the impulse, its point and the angular impulse must be finite (ODE "
        "aborts on a NaN)");
  dBodyID body = impl_->bodyOf(entity);
  if (body == nullptr) return;
  dBodyEnable(body);
  dMass mass;
  dBodyGetMass(body, &mass);
  Eigen::Matrix3d inertia_body;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) inertia_body(r, c) = mass.I[4 * r + c];
  const dReal* q = dBodyGetQuaternion(body);
  const Eigen::Matrix3d rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  const Eigen::Vector3d centre = ode::vec(dBodyGetPosition(body));
  const Eigen::Vector3d velocity = ode::vec(dBodyGetLinearVel(body)) + impulse_Ns / mass.mass;
  const Eigen::Vector3d angular_impulse = (point_m - centre).cross(impulse_Ns) + angular_impulse_Nms;
  const Eigen::Vector3d omega = ode::vec(dBodyGetAngularVel(body)) +
                                rotation * inertia_body.inverse() * (rotation.transpose() * angular_impulse);
  dBodySetLinearVel(body, velocity.x(), velocity.y(), velocity.z());
  dBodySetAngularVel(body, omega.x(), omega.y(), omega.z());
}

void World::shiftCar(CarId id, const Eigen::Vector3d& shift_m) {
  shift({EntityRef::Kind::Car, id}, shift_m);
}

void World::shift(EntityRef entity, const Eigen::Vector3d& shift_m) {
  dBodyID body = impl_->bodyOf(entity);
  if (body == nullptr) return;
  if (entity.kind == EntityRef::Kind::Obstacle) dBodyEnable(body);
  const Eigen::Vector3d p = ode::vec(dBodyGetPosition(body)) + shift_m;
  dBodySetPosition(body, p.x(), p.y(), p.z());
}

double World::inverseMass_per_kg(EntityRef entity) const {
  dBodyID body = impl_->bodyOf(entity);
  if (body == nullptr) return 0.0;
  dMass mass;
  dBodyGetMass(body, &mass);
  return mass.mass > 0 ? 1.0 / mass.mass : 0.0;
}

double World::obstacleKineticEnergy_J(ObstacleId id) const {
  const ObstacleEntry& o = impl_->obstacles.at(id);
  if (o.body == nullptr) return 0.0;
  dMass mass;
  dBodyGetMass(o.body, &mass);
  const Eigen::Vector3d v = ode::vec(dBodyGetLinearVel(o.body));
  // ODE's inertia is in the body's axes: the turn taken into them.
  const Eigen::Vector3d w_world = ode::vec(dBodyGetAngularVel(o.body));
  dVector3 w_body;
  dBodyVectorFromWorld(o.body, w_world.x(), w_world.y(), w_world.z(), w_body);
  const Eigen::Vector3d w(w_body[0], w_body[1], w_body[2]);
  Eigen::Matrix3d inertia;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) inertia(r, c) = mass.I[4 * r + c];
  return 0.5 * mass.mass * v.squaredNorm() + 0.5 * w.dot(inertia * w);
}

void World::step() {
  Impl& m = *impl_;
  const double dt = fixedDt_s();
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  // ODE's simple space's collision pass, its pairs from the grid: the boxes cleaned (as dSpaceCollide
  // does first, which keeps the space's order of geoms as it was), then every pair of boxes that overlap,
  // in the space's order, not on one body.
  dSpaceClean(m.space);
  m.geom_grid.build(m.space);  // nothing moves while the wheels cast their rays, nor until the pass
  for (auto& c : m.cars) c->applyForces(dt, m.geom_grid);
  const auto t1 = Clock::now();
  m.contacts.clear();
  m.feedback.clear();
  m.feedback_sign.clear();
  m.geom_grid.pairs(m.pair_scratch);
  for (const uint64_t pair : m.pair_scratch) {
    const int i = static_cast<int>(pair >> 32), j = static_cast<int>(pair & 0xffffffffu);
    dGeomID g1 = m.geom_grid.geom(i), g2 = m.geom_grid.geom(j);
    if (!dGeomIsEnabled(g1) || !dGeomIsEnabled(g2)) continue;
    dBodyID b1 = dGeomGetBody(g1);
    if (b1 != nullptr && b1 == dGeomGetBody(g2)) continue;
    if (ode::boxesMeet(m.geom_grid.box(i), m.geom_grid.box(j))) Impl::nearCallback(&m, g1, g2);
  }
  const auto t2 = Clock::now();
  // ODE's quick step shuffles constraints with one global random seed: give it this world's own.
  dRandSetSeed(m.random_seed);
  dWorldQuickStep(m.world, dt);
  m.random_seed = dRandGetSeed();
  // Orientations ODE's normalisation keeps, so a saved state is put back bit for bit (ode_support.hpp).
  for (auto& c : m.cars)
    if (dBodyIsEnabled(c->body_)) ode::keepOrientationRestorable(c->body_);
  for (auto& o : m.obstacles)
    if (o.body && dBodyIsEnabled(o.body)) ode::keepOrientationRestorable(o.body);
  m.sleepRestingObstacles();
  for (std::size_t i = 0; i < m.contacts.size(); ++i)
    m.contacts[i].force_on_a_N = m.feedback_sign[i] * ode::vec(m.feedback[i].f1);
  dJointGroupEmpty(m.contact_joints);
  m.time_s += dt;
  ++m.steps;
  auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  m.timings = {ms(t1 - t0), ms(t2 - t1), ms(Clock::now() - t2)};
}

WorldTimings World::lastTimings() const {
  return impl_->timings;
}

int World::advance(double dt_s) {
  if (!(std::isfinite(dt_s) && dt_s > 0))
    throw deform::InputError(detail::fieldMessage("dt_s", "time step must be finite and positive", dt_s));
  Impl& m = *impl_;
  const double fixed = fixedDt_s();
  m.accumulator_s += dt_s;
  int taken = 0;
  while (m.accumulator_s >= fixed * (1 - 1e-9)) {
    step();
    m.accumulator_s -= fixed;
    ++taken;
  }
  if (m.accumulator_s < 0) m.accumulator_s = 0;
  return taken;
}

double World::fixedDt_s() const {
  return 1.0 / impl_->settings.physics_rate_hz;
}
double World::time_s() const {
  return impl_->time_s;
}
uint64_t World::stepCount() const {
  return impl_->steps;
}
const std::vector<ContactPoint>& World::contacts() const {
  return impl_->contacts;
}

std::vector<CarContact> World::carContacts(CarId id) const {
  const EntityRef self{EntityRef::Kind::Car, id};
  const Pose frame = car(id).vehiclePose();
  const Eigen::Quaterniond to_vehicle = frame.orientation.conjugate();
  std::vector<CarContact> out;
  for (const ContactPoint& c : impl_->contacts) {
    if (!(c.a == self) && !(c.b == self)) continue;
    // ODE's normal points from b into a; the force is on a.
    const double sign = c.a == self ? 1.0 : -1.0;
    CarContact contact;
    contact.other = c.a == self ? c.b : c.a;
    contact.point_m = frame.toLocal(c.position_m);
    contact.normal = to_vehicle * (sign * c.normal);
    contact.depth_m = c.depth_m;
    contact.impulse_N_s = to_vehicle * (sign * c.force_on_a_N * fixedDt_s());
    out.push_back(contact);
  }
  return out;
}

void World::saveState(StateWriter& out) const {
  const Impl& m = *impl_;
  out.u64(m.cars.size());
  if (!out.forHash()) out.u64(m.obstacles.size());
  out.real(m.time_s);
  out.real(m.accumulator_s);
  out.u64(m.steps);
  out.u64(static_cast<uint64_t>(m.random_seed));
  for (std::size_t i = 0; i < m.cars.size(); ++i) {
    out.real(m.crush_allowance_m[i]);
    out.flag(m.crush_coupled[i] != 0);
    m.cars[i]->saveState(out);
  }
  for (const auto& o : m.obstacles)
    if (o.body) {
      ode::saveBody(out, o.body);
      out.u64(static_cast<uint64_t>(o.still_steps));
    }
  ode::saveGeomOrder(out, m.space, m.geoms(), out.forHash());
}

void World::restoreState(StateReader& in) {
  Impl& m = *impl_;
  in.expect(in.u64() == m.cars.size(), "car count does not match the scene");
  in.expect(in.u64() == m.obstacles.size(), "obstacle count does not match the scene");
  m.time_s = in.real();
  m.accumulator_s = in.real();
  m.steps = in.u64();
  m.random_seed = static_cast<unsigned long>(in.u64());
  for (std::size_t i = 0; i < m.cars.size(); ++i) {
    const double allowance_m = in.real();
    const bool coupled = in.flag();
    in.expect(std::isfinite(allowance_m) && allowance_m >= 0, "crush allowance out of range");
    in.expect(coupled == (m.crush_coupled[i] != 0), "crush coupling does not match the scene");
    m.cars[i]->restoreState(in);
    // The shrunk-hull backstop follows the (possibly re-hulled) hull and the stroke left, as after a
    // re-hull; rigid parts never change.
    if (allowance_m > 0) setCrushAllowance(static_cast<CarId>(i), allowance_m);
  }
  for (auto& o : m.obstacles)
    if (o.body) {
      ode::restoreBody(in, o.body, "obstacle");
      const uint64_t still = in.u64();
      in.expect(still <= INT32_MAX, "obstacle sleep countdown out of range");
      o.still_steps = static_cast<int>(still);
    }
  m.contacts.clear();
  m.feedback.clear();
  m.feedback_sign.clear();
  ode::restoreGeomOrder(in, m.space, m.geoms());
}

uint64_t World::stateHash() const {
  StateWriter out(true);
  saveState(out);
  return fnv1a(out.bytes().data(), out.bytes().size());
}

}  // namespace vehicle
