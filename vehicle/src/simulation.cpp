// A World with deformable cars and the crush coupling (simulation.hpp; DESIGN.md section 5).
#include <vehicle/simulation.hpp>

#include "crush_shapes.hpp"

#include <deform/body_settings.hpp>
#include <deform/body_state.hpp>
#include <deform/deformable_body.hpp>
#include <deform/error.hpp>
#include <deform/masses.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vehicle {
namespace {

// Whether `point` lies inside the closed outward-wound surface `mesh`, at least `margin_m` from every face.
bool enclosesWithMargin(const deform::ControlMesh& mesh, const Eigen::Vector3d& point, double margin_m) {
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.points_m[t[0]];
    const Eigen::Vector3d n = (mesh.points_m[t[1]] - a).cross(mesh.points_m[t[2]] - a);
    const double length = n.norm();
    if (!(length > 0)) continue;
    if ((point - a).dot(n) / length > -margin_m) return false;
  }
  return true;
}

using Clock = std::chrono::steady_clock;

double ms(Clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

std::string field(const char* member) {
  return std::string("vehicle.deformation.") + member;
}

void require(bool ok, const char* member, const std::string& rule, double value) {
  if (!ok) throw deform::InputError(field(member) + ": " + rule + " (got " + std::to_string(value) + ")");
}

/// Kinetic energy of a rigid body: translation plus rotation (I in the body axes) [J].
double kineticEnergy(const Car& car) {
  const Eigen::Vector3d v = car.velocity_mps();
  const Eigen::Vector3d w = car.bodyPose().orientation.conjugate() * car.angularVelocity_rad_s();
  return 0.5 * car.mass_kg() * v.squaredNorm() + 0.5 * w.dot(car.inertia_kg_m2() * w);
}

bool crushable(const World& world, EntityRef e) {
  if (e.kind == EntityRef::Kind::Car) return true;
  const ObstacleKind kind = world.obstacleKind(e.index);
  return kind != ObstacleKind::Ground && kind != ObstacleKind::Ramp && kind != ObstacleKind::Vegetation;
}

/// Vegetation: rigid for the hull (knocked over by it), denting the body by its contact impulses.
bool vegetation(const World& world, EntityRef e) {
  return e.kind == EntityRef::Kind::Obstacle && world.obstacleKind(e.index) == ObstacleKind::Vegetation;
}

/// An obstacle standing on the ground: its lowest point within 5 cm of z = 0 and, for a post or a box, an
/// axis within 30 degrees of the vertical. Only such an obstacle is extended into the ground (so a point
/// deep in a wall is never pushed out under it): a knocked-over tree lying from the ground across the
/// bonnet, extended 2 m down, would be a slab through the car's front.
bool standsOnGround(const ObstacleShape& shape) {
  if (shape.type == ShapeType::HalfSpace || supportPoint(shape, -Eigen::Vector3d::UnitZ()).z() >= 0.05)
    return false;
  const double upright = std::cos(std::numbers::pi / 6);
  if (shape.type == ShapeType::Cylinder || shape.type == ShapeType::Capsule) {
    const Eigen::Vector3d along = shape.b_m - shape.a_m;
    return std::abs(along.z()) > upright * along.norm();
  }
  if (shape.type == ShapeType::Box) return shape.axes.row(2).cwiseAbs().maxCoeff() > upright;  // unit axes
  return true;
}

}  // namespace

deform::Material DeformationSettings::sedanMaterial() {
  deform::Material m;  // the deform defaults are the sedan's calibration (docs/CRASH_CALIBRATION.md)
  return m;
}

void checkDeformationSettings(const DeformationSettings& s) {
  require(s.control_points >= 4 && s.control_points <= 5000, "control_points", "must be in [4, 5000]",
          static_cast<double>(s.control_points));
  require(std::isfinite(s.alpha) && s.alpha > 0, "alpha", "must be finite and positive", s.alpha);
  require(s.substeps >= 1 && s.substeps <= 1000, "substeps", "must be in [1, 1000]", s.substeps);
  require(s.iterations >= 1 && s.iterations <= 1000, "iterations", "must be in [1, 1000]", s.iterations);
  require(std::isfinite(s.max_deviation_m) && s.max_deviation_m > 0, "max_deviation_m",
          "must be finite and positive", s.max_deviation_m);
  deform::checkMaterial(s.material, "vehicle.deformation.material");
  require(std::isfinite(s.shell_mass_fraction) && s.shell_mass_fraction > 0 && s.shell_mass_fraction <= 1,
          "shell_mass_fraction", "must be in (0, 1]", s.shell_mass_fraction);
  require(std::isfinite(s.damping) && s.damping >= 0, "damping", "must be finite and >= 0", s.damping);
  require(std::isfinite(s.contact_friction) && s.contact_friction >= 0, "contact_friction",
          "must be finite and >= 0", s.contact_friction);
  require(std::isfinite(s.crush_allowance_m) && s.crush_allowance_m >= 0, "crush_allowance_m",
          "must be finite and >= 0", s.crush_allowance_m);
  require(std::isfinite(s.inertial_scale) && s.inertial_scale >= 0, "inertial_scale",
          "must be finite and >= 0", s.inertial_scale);
  require(std::isfinite(s.visual_impulse_scale) && s.visual_impulse_scale >= 0, "visual_impulse_scale",
          "must be finite and >= 0", s.visual_impulse_scale);
}

/// One deformable car: its body and the bookkeeping of the coupling and the metrics.
struct DeformableCar {
  CarId id = 0;
  DeformationSettings settings;
  deform::ControlMesh mesh;
  std::shared_ptr<const deform::BodySettings> body_settings;
  std::unique_ptr<deform::DeformableBody> body;
  CrushShapes shapes;               ///< what the car touches at the end of the step (vehicle frame)
  CrushShapes substep_shapes;       ///< the same, where it is at a substep
  std::vector<EntityRef> touching;  ///< crushable entities in contact this step
  /// Its control points in the world before this step's deformation: what other cars dent against
  /// (taken for every car first, so the order cars are stepped in does not matter).
  ObstacleShape world_shape;

  // Coupling.
  bool hull_dirty = false;  ///< dented since the collision hull was last rebuilt
  int quiet_steps = 0;      ///< steps without a control point in contact
  Eigen::Vector3d previous_velocity_mps{0, 0, 0};
  double previous_kinetic_J = 0;

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
  double step_crush_work_J = 0;  ///< kinetic energy the body's reaction took from the chassis this step [J]
  double step_other_work_J = 0;  ///< work every other force took from it this step [J]
};

struct Simulation::Impl {
  World world;
  std::vector<std::unique_ptr<DeformableCar>> cars;
  std::vector<int> index_of;  ///< per CarId: index into cars, -1 when rigid
  StepTimings timings;

  explicit Impl(const WorldSettings& s) : world(s) {}

  DeformableCar& of(CarId id) const {
    if (id >= index_of.size() || index_of[id] < 0)
      throw std::out_of_range("car " + std::to_string(id) + " does not deform");
    return *cars[static_cast<std::size_t>(index_of[id])];
  }

  std::vector<Eigen::Vector3d> car_velocity_before;  ///< per CarId: velocity before this step [m/s]
  Eigen::Vector3d velocityBefore(EntityRef e) const {
    if (e.kind == EntityRef::Kind::Car && e.index < car_velocity_before.size())
      return car_velocity_before[e.index];
    return velocityOf(e);
  }

  Eigen::Vector3d velocityOf(EntityRef e) const {
    if (e.kind == EntityRef::Kind::Car) return world.car(e.index).velocity_mps();
    return Eigen::Vector3d::Zero();  // obstacles: static or slow next to a car
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
    const Pose pose = world.car(dc.id).vehiclePose();
    ObstacleShape s;
    s.type = ShapeType::Convex;
    s.centre_m.setZero();
    for (const auto& p : dc.body->state().positions_m) {
      s.vertices_m.push_back(pose.toWorld(p));
      s.centre_m += s.vertices_m.back();
    }
    s.centre_m /= static_cast<double>(s.vertices_m.size());
    return s;
  }

  void stepCar(DeformableCar& dc);
  void updateMetrics(DeformableCar& dc, const Eigen::Vector3d& velocity_before, double kinetic_before);
};

Simulation::Simulation(const WorldSettings& settings) : impl_(std::make_unique<Impl>(settings)) {}
Simulation::~Simulation() = default;

World& Simulation::world() {
  return impl_->world;
}
const World& Simulation::world() const {
  return impl_->world;
}

CarId Simulation::addDeformableCar(const deform::VehicleModel& model, const VehicleSettings& car,
                                   const CarStart& start, const DeformationSettings& deformation) {
  checkDeformationSettings(deformation);
  auto dc = std::make_unique<DeformableCar>();
  dc->settings = deformation;
  std::vector<Eigen::Vector3d> points;
  points.reserve(model.body.positions_m.size());
  for (const auto& p : model.body.positions_m) points.push_back(p.cast<double>());
  const std::string source = model.source.empty() ? "vehicle model" : model.source;
  dc->mesh = deform::buildControlMesh(points, deformation.control_points, source.c_str());
  const deform::MassSplit masses =
      deform::distributeMass(dc->mesh, car.mass_kg * deformation.shell_mass_fraction);
  deform::BodyDescription description;
  description.material = deformation.material;
  description.max_deviation_m = deformation.max_deviation_m;
  dc->body_settings =
      std::make_shared<const deform::BodySettings>(deform::createBodySettings(dc->mesh, masses, description));
  deform::SolverParams params;
  params.substeps = static_cast<uint32_t>(deformation.substeps);
  params.iterations = static_cast<uint32_t>(deformation.iterations);
  params.damping_per_s = deformation.damping;
  params.inertial_scale = deformation.inertial_scale;
  dc->body = std::make_unique<deform::DeformableBody>(dc->body_settings, params);

  const CarId id = impl_->world.addCar(model, car, start);
  dc->id = id;
  if (deformation.coupling == Coupling::Crush)
    impl_->world.setCrushAllowance(id, deformation.crush_allowance_m);
  const Car& c = impl_->world.car(id);
  dc->previous_velocity_mps = c.velocity_mps();
  dc->previous_kinetic_J = kineticEnergy(c);
  if (impl_->index_of.size() <= id) impl_->index_of.resize(id + 1, -1);
  impl_->index_of[id] = static_cast<int>(impl_->cars.size());
  impl_->cars.push_back(std::move(dc));
  return id;
}

void Simulation::step() {
  Impl& m = *impl_;
  const auto t0 = Clock::now();
  // The crush forces found last step act during this one (on the car, and their reaction on free bodies).
  std::vector<Eigen::Vector3d> velocity_before, omega_before;
  std::vector<double> kinetic_before;
  m.car_velocity_before.clear();
  for (CarId c = 0; c < m.world.carCount(); ++c)
    m.car_velocity_before.push_back(m.world.car(c).velocity_mps());
  for (auto& dc : m.cars) {
    const Car& car = m.world.car(dc->id);
    velocity_before.push_back(car.velocity_mps());
    omega_before.push_back(car.angularVelocity_rad_s());
    kinetic_before.push_back(kineticEnergy(car));
  }
  m.world.step();
  const auto t1 = Clock::now();
  for (auto& dc : m.cars) dc->world_shape = m.snapshotShape(*dc);
  const double dt = m.world.fixedDt_s();
  for (std::size_t i = 0; i < m.cars.size(); ++i) {
    DeformableCar& dc = *m.cars[i];
    const Car& car = m.world.car(dc.id);
    // Work of every force on the chassis over the step, at the midpoint velocities of the points they act
    // at [J]: the crush force, and (for the energy balance) tyres and suspension, ODE contacts, drag and
    // gravity.
    const Eigen::Vector3d v_mid = 0.5 * (velocity_before[i] + car.velocity_mps());
    const Eigen::Vector3d w_mid = 0.5 * (omega_before[i] + car.angularVelocity_rad_s());
    const Eigen::Vector3d com = car.bodyPose().position_m;
    auto pointVelocity = [&](const Eigen::Vector3d& p) {
      return Eigen::Vector3d(v_mid + w_mid.cross(p - com));
    };
    double taken_J = 0;  // by everything else
    for (const WheelState& w : car.wheels())
      if (w.in_contact) taken_J -= w.force_N.dot(pointVelocity(w.contact_point_m)) * dt;
    const EntityRef self{EntityRef::Kind::Car, dc.id};
    for (const ContactPoint& c : m.world.contacts()) {
      if (!(c.a == self) && !(c.b == self)) continue;
      const Eigen::Vector3d force = c.a == self ? c.force_on_a_N : Eigen::Vector3d(-c.force_on_a_N);
      taken_J -= force.dot(pointVelocity(c.position_m)) * dt;
    }
    const VehicleSettings& vs = car.settings();
    const Eigen::Vector3d drag =
        -0.5 * vs.air_density_kg_m3 * vs.drag_area_m2 * velocity_before[i].norm() * velocity_before[i];
    taken_J -= (drag + car.mass_kg() * m.world.settings().gravity_mps2).dot(v_mid) * dt;
    dc.step_other_work_J = taken_J;
    m.stepCar(dc);
    m.updateMetrics(dc, velocity_before[i], kinetic_before[i]);
  }
  m.timings = {ms(t1 - t0), ms(Clock::now() - t1)};
}

int Simulation::run(double duration_s) {
  const int steps = static_cast<int>(std::llround(duration_s / impl_->world.fixedDt_s()));
  for (int k = 0; k < steps; ++k) step();
  return std::max(steps, 0);
}

void Simulation::Impl::stepCar(DeformableCar& dc) {
  Car& car = world.car(dc.id);
  const Pose frame = car.vehiclePose();
  const Eigen::Quaterniond to_vehicle = frame.orientation.conjugate();
  const double dt = world.fixedDt_s();
  const std::vector<CarContact> contacts = world.carContacts(dc.id);
  const bool crush = dc.settings.coupling == Coupling::Crush;

  // What the car touches (not the ground, not ramps), each once.
  dc.touching.clear();
  for (const CarContact& c : contacts)
    if (crushable(world, c.other) &&
        std::find(dc.touching.begin(), dc.touching.end(), c.other) == dc.touching.end())
      dc.touching.push_back(c.other);

  // The obstacles where they are at the end of the step (vehicle frame), with their velocities relative to
  // the chassis: deform moves them along those through its substeps.
  deform::StepInputs inputs;
  inputs.contact_friction = dc.settings.contact_friction;
  dc.shapes.clear();
  for (const EntityRef& other : dc.touching) {
    const ObstacleShape world_shape = worldShapeOf(other);
    const ObstacleShape local = transformShape(world_shape, frame);
    const Eigen::Vector3d relative_mps = to_vehicle * (velocityOf(other) - car.velocity_mps());
    // Sweep away from the car, against the contact normals. A point can be as deep as the deepest contact
    // at the start of the step plus the step's closing travel; twice that keeps the near face the nearest.
    Eigen::Vector3d normal{0, 0, 0};
    double deepest_m = 0;
    for (const CarContact& c : contacts)
      if (c.other == other) {
        normal += c.normal;
        deepest_m = std::max(deepest_m, c.depth_m);
      }
    Eigen::Vector3d sweep{0, 0, 0};
    if (normal.norm() > 1e-12) {
      normal.normalize();
      const double closing = std::max(0.0, relative_mps.dot(normal));
      sweep = -(2.0 * (deepest_m + closing * dt) + 0.05) * normal;
    }
    // An obstacle standing on the ground reaches into it.
    Eigen::Vector3d down{0, 0, 0};
    if (standsOnGround(world_shape)) down = to_vehicle * Eigen::Vector3d(0, 0, -2.0);
    const bool post =
        other.kind == EntityRef::Kind::Obstacle && world.obstacleKind(other.index) == ObstacleKind::Post;
    // Every obstacle is met between the control points too (face contacts): a post or another car's
    // corner thinner than the point spacing pushes the faces and edges it meets, at any level of detail.
    dc.shapes.add(local, sweep, down, post, true);
    inputs.contact_velocity_mps.push_back(relative_mps);
  }
  inputs.contacts = dc.shapes.shapes();
  inputs.surface_contact = dc.shapes.surfaceFlags();
  // Crush: the core is the chassis, a heavy particle inside deform's substeps; what the body hands it is
  // handed to ODE below, in this step. Visual: the chassis is rigid to what it hits (ODE's contact).
  if (crush) inputs.core_mass_kg = car.mass_kg();

  // Visual (and vegetation in either coupling): the contact impulses go to the nearest control points
  // (inverse-distance weights).
  const deform::BodyState& state = dc.body->state();
  if (dc.settings.visual_impulse_scale > 0) {
    constexpr std::size_t kNearest = 4;
    const bool visual = !crush;
    for (const CarContact& c : contacts) {
      const bool dents = (visual && crushable(world, c.other)) || vegetation(world, c.other);
      if (!dents || c.impulse_N_s.squaredNorm() == 0) continue;
      std::vector<std::pair<double, uint32_t>> near;
      for (uint32_t p = 0; p < state.positions_m.size(); ++p)
        near.emplace_back((state.positions_m[p] - c.point_m).norm(), p);
      const std::size_t k = std::min(kNearest, near.size());
      std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(k), near.end());
      double total = 0;
      for (std::size_t j = 0; j < k; ++j) total += 1.0 / (near[j].first + 0.05);
      for (std::size_t j = 0; j < k; ++j)
        inputs.impulses.push_back(
            {near[j].second,
             dc.settings.visual_impulse_scale * (1.0 / (near[j].first + 0.05)) / total * c.impulse_N_s});
    }
  }

  if (dc.settings.inertial_scale > 0) {
    inputs.chassis.acceleration_mps2 = to_vehicle * ((car.velocity_mps() - dc.previous_velocity_mps) / dt);
    inputs.chassis.angular_velocity_radps = to_vehicle * car.angularVelocity_rad_s();
    inputs.chassis.gravity_mps2 = to_vehicle * world.settings().gravity_mps2;
  }

  dc.plastic_before_step_J = state.plastic_work_J;
  const deform::StepReport report = dc.body->step(inputs, dt);
  dc.damping_loss_J += report.damping_loss_J;
  dc.contact_work_J += report.contact_work_J;

  // Reaction, equal and opposite in this step: the momentum the body handed its core goes to the chassis
  // (and the core's travel within the step to its position); the momentum the obstacles gave the points
  // goes back to a free obstacle (a pushed box), at the contact points' centre.
  dc.step_crush_work_J = 0;
  if (crush) {
    const double kinetic_before_J = kineticEnergy(car);
    world.applyImpulse({EntityRef::Kind::Car, dc.id}, frame.orientation * report.core_impulse_Ns,
                       frame.toWorld(dc.body_settings->core_m),
                       frame.orientation * report.core_angular_impulse_Nms);
    world.shiftCar(dc.id, frame.orientation * report.core_displacement_m);
    dc.step_crush_work_J = kinetic_before_J - kineticEnergy(car);
    if (report.contact_impulse_Ns.squaredNorm() > 0)
      for (const EntityRef& other : dc.touching) {
        if (other.kind == EntityRef::Kind::Car && other.index < index_of.size() && index_of[other.index] >= 0)
          continue;  // another deformable car takes its share through its own body
        world.applyImpulse(
            other, -(frame.orientation * report.contact_impulse_Ns) / static_cast<double>(dc.touching.size()),
            interiorPoint(worldShapeOf(other)));
      }
  }
  dc.previous_velocity_mps = car.velocity_mps();

  // The collision hull follows the dent once the contact is over (never during it, DESIGN.md sec. 5): no
  // point has touched anything for 0.1 s, the body is at rest, and the old hull touches nothing it could
  // crush (the new hull is convex: around a pole's notch it would fill the notch, and its backstop would
  // throw the car off the pole).
  if (report.contact_points > 0) {
    dc.hull_dirty = true;
    dc.quiet_steps = 0;
  } else {
    ++dc.quiet_steps;
  }
  const int quiet_needed = std::max(1, static_cast<int>(std::ceil(0.1 / dt)));
  if (crush && dc.hull_dirty && dc.quiet_steps >= quiet_needed && dc.touching.empty() &&
      report.max_speed_mps < 0.05) {
    const std::size_t n = std::max<std::size_t>(4, car.settings().collision_points);
    const deform::ControlMesh dented =
        deform::buildControlMesh(dc.body->state().positions_m, n, "dented body");
    // A body crushed through its own centre of mass (a small car, a deep dent) keeps its old hull: ODE's
    // convex geom needs the centre inside (its planes' offsets positive), or it warns and mis-collides.
    if (enclosesWithMargin(dented, dc.body_settings->core_m, 0.01)) {
      car.setCollisionHull(dented);
      const double used = deform::maxDeviation(*dc.body_settings, dc.body->state());
      world.setCrushAllowance(dc.id, std::max(0.0, dc.settings.crush_allowance_m - used));
    }
    dc.hull_dirty = false;
  }
}

void Simulation::Impl::updateMetrics(DeformableCar& dc, const Eigen::Vector3d& velocity_before,
                                     double kinetic_before) {
  const Car& car = world.car(dc.id);
  CrashMetrics& mt = dc.metrics;
  const deform::BodyState& s = dc.body->state();

  // Divergence (MuJoCo-style): non-finite or beyond 1e10 anywhere.
  auto bad = [](const Eigen::Vector3d& v) { return !v.allFinite() || v.cwiseAbs().maxCoeff() > 1e10; };
  for (const auto& x : s.positions_m)
    if (bad(x)) mt.diverged = true;
  if (bad(car.bodyPose().position_m) || bad(car.velocity_mps())) mt.diverged = true;

  if (!mt.impacted && !dc.touching.empty()) {
    // First impact with the first thing touched: velocities before the step, positions now.
    const EntityRef other = dc.touching.front();
    mt.impacted = true;
    dc.impact_other = other;
    dc.impact_relative_velocity_mps = velocity_before - velocityBefore(other);
    dc.impact_com_m = car.bodyPose().position_m;
    dc.impact_other_m = interiorPoint(worldShapeOf(other));
    dc.impact_normal_sum.setZero();
    dc.impact_steps = 0;
    mt.energy.kinetic_initial_J = kinetic_before;
    dc.plastic_at_impact_J = dc.plastic_before_step_J;  // this step's plastic work counts
    dc.damping_at_impact_J = dc.damping_loss_J;
    dc.contact_work_at_impact_J = dc.contact_work_J;
  }
  // The impact normal: the depth-weighted normals of the contacts with what was hit over the first 10 ms
  // (the very first contact of two rounded fronts can have any normal).
  const int settle_steps = std::max(1, static_cast<int>(std::lround(0.01 / world.fixedDt_s())));
  if (mt.impacted && dc.impact_steps < settle_steps) {
    ++dc.impact_steps;
    for (const CarContact& c : world.carContacts(dc.id))
      if (c.other == dc.impact_other)
        dc.impact_normal_sum += (c.depth_m + 1e-6) * (car.vehiclePose().orientation * c.normal);
    if (dc.impact_normal_sum.norm() > 1e-12) {
      dc.impact_normal = dc.impact_normal_sum.normalized();
      // Crash tests measure along the road: a mostly horizontal normal is taken horizontal, so the car's
      // pitching and bouncing do not count as rebound.
      const Eigen::Vector3d horizontal_normal(dc.impact_normal.x(), dc.impact_normal.y(), 0);
      if (horizontal_normal.norm() > 0.5) dc.impact_normal = horizontal_normal.normalized();
      const Eigen::Vector3d horizontal =
          car.vehiclePose().orientation.conjugate() * Eigen::Vector3d(-dc.impact_normal);
      dc.impact_direction_vehicle = Eigen::Vector3d(horizontal.x(), horizontal.y(), 0);
      if (dc.impact_direction_vehicle.norm() < 1e-6) dc.impact_direction_vehicle = Eigen::Vector3d::UnitX();
      mt.impact_speed_mps = std::max(0.0, -dc.impact_relative_velocity_mps.dot(dc.impact_normal));
      dc.impact_separation_m = dc.impact_normal.dot(dc.impact_com_m - dc.impact_other_m);
    }
  }

  mt.max_deviation_m = std::max(mt.max_deviation_m, deform::maxDeviation(*dc.body_settings, s));
  deform::Penetration pen;
  for (const auto& shape : dc.shapes.exactShapes())
    for (const auto& x : s.positions_m)
      if (deform::penetration(shape, x, pen))
        mt.max_penetration_m = std::max(mt.max_penetration_m, pen.depth_m);

  if (!mt.impacted) return;
  // The rebound is the separation speed: measured while the car touches what it hit and in the step it
  // leaves it, never afterwards (a car steering away from a wall it grazed is not a rebound).
  const bool in_contact =
      std::find(dc.touching.begin(), dc.touching.end(), dc.impact_other) != dc.touching.end();
  const Eigen::Vector3d relative = car.velocity_mps() - velocityOf(dc.impact_other);
  if (in_contact || dc.in_contact)
    mt.rebound_speed_mps = std::max(mt.rebound_speed_mps, relative.dot(dc.impact_normal));
  dc.in_contact = in_contact;
  mt.restitution = mt.impact_speed_mps > 1e-9 ? mt.rebound_speed_mps / mt.impact_speed_mps : 0.0;
  const double separation =
      dc.impact_normal.dot(car.bodyPose().position_m - interiorPoint(worldShapeOf(dc.impact_other)));
  mt.max_dynamic_crush_m = std::max(mt.max_dynamic_crush_m, dc.impact_separation_m - separation);
  if (separation < 0) mt.tunnelled = true;

  EnergyTerms& e = mt.energy;
  e.crush_work_J += dc.step_crush_work_J;
  e.other_work_J += dc.step_other_work_J;
  e.plastic_work_J = s.plastic_work_J - dc.plastic_at_impact_J;
  e.kinetic_final_J = kineticEnergy(car);
  e.damping_loss_J = dc.damping_loss_J - dc.damping_at_impact_J;
  e.body_energy_J = deform::bodyEnergy(*dc.body_settings, s).total_J();
  e.contact_work_J = dc.contact_work_J - dc.contact_work_at_impact_J;
  e.dissipated_J = e.damping_loss_J + e.other_work_J;
  e.balance_error_J = e.crush_work_J - e.plastic_work_J - e.damping_loss_J - e.body_energy_J;
}

std::size_t Simulation::deformableCount() const {
  return impl_->cars.size();
}

bool Simulation::isDeformable(CarId car) const {
  return car < impl_->index_of.size() && impl_->index_of[car] >= 0;
}

std::vector<Eigen::Vector3d> Simulation::controlDisplacements(CarId car) const {
  const DeformableCar& dc = impl_->of(car);
  std::vector<Eigen::Vector3d> out;
  const auto& x = dc.body->state().positions_m;
  out.reserve(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) out.push_back(x[i] - dc.body_settings->rest_positions_m[i]);
  return out;
}

const std::vector<Eigen::Vector3d>& Simulation::controlRestPoints(CarId car) const {
  return impl_->of(car).body_settings->rest_positions_m;
}

const std::vector<Eigen::Vector3d>& Simulation::controlPoints(CarId car) const {
  return impl_->of(car).body->state().positions_m;
}

const deform::ControlMesh& Simulation::controlMesh(CarId car) const {
  return impl_->of(car).mesh;
}

const DeformationSettings& Simulation::deformationSettings(CarId car) const {
  return impl_->of(car).settings;
}

const deform::DeformableBody& Simulation::body(CarId car) const {
  return *impl_->of(car).body;
}

CrashMetrics Simulation::metrics(CarId car) const {
  const DeformableCar& dc = impl_->of(car);
  CrashMetrics out = dc.metrics;
  if (!out.impacted) return out;
  // At the height of the struck end's most protruding rest point (the bumper, for a frontal impact).
  const auto& rest = dc.body_settings->rest_positions_m;
  std::size_t lead = 0;
  for (std::size_t i = 1; i < rest.size(); ++i)
    if (rest[i].dot(dc.impact_direction_vehicle) > rest[lead].dot(dc.impact_direction_vehicle)) lead = i;
  const std::vector<double> crush =
      crushProfile(dc.mesh, dc.body->state().positions_m, dc.impact_direction_vehicle, rest[lead].z());
  for (std::size_t i = 0; i < rest.size(); ++i)
    out.max_dent_m =
        std::max(out.max_dent_m,
                 -(dc.body->state().positions_m[i] - rest[i]).dot(dc.impact_direction_vehicle.normalized()));
  if (!crush.empty()) {
    double sum = 0;
    for (double c : crush) {
      sum += c;
      out.max_residual_crush_m = std::max(out.max_residual_crush_m, c);
    }
    out.residual_crush_m = sum / static_cast<double>(crush.size());
  }
  return out;
}

StepTimings Simulation::lastTimings() const {
  return impl_->timings;
}

uint64_t Simulation::stateHash() const {
  uint64_t hash = impl_->world.stateHash();
  for (const auto& dc : impl_->cars) {
    const uint64_t body = deform::hashState(dc->body->state());
    hash = fnv1a(&body, sizeof body, hash);
  }
  return hash;
}

}  // namespace vehicle
