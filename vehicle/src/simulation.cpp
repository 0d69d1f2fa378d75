// A World with deformable cars and the crush coupling (simulation.hpp; DESIGN.md section 5): the API and
// the step. One car's deformation is crush_coupling.cpp, its metrics crash_metrics_update.cpp.
#include "simulation_impl.hpp"

#include <deform/error.hpp>
#include <deform/masses.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vehicle {
namespace {

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

}  // namespace

double kineticEnergy(const Car& car) {
  const Eigen::Vector3d v = car.velocity_mps();
  const Eigen::Vector3d w = car.bodyPose().orientation.conjugate() * car.angularVelocity_rad_s();
  return 0.5 * car.chassisMass_kg() * v.squaredNorm() + 0.5 * w.dot(car.chassisInertia_kg_m2() * w);
}

double Simulation::Impl::carKineticEnergy(const DeformableCar& dc) const {
  const Car& car = world.car(dc.id);
  double kinetic_J = kineticEnergy(car);
  if (dc.settings.coupling != Coupling::Crush) return kinetic_J;
  const Eigen::Quaterniond to_vehicle = car.vehiclePose().orientation.conjugate();
  const Eigen::Vector3d v = to_vehicle * car.velocity_mps(), w = to_vehicle * car.angularVelocity_rad_s();
  const deform::BodyState& s = dc.body->state();
  const std::vector<double>& m = dc.body_settings->mass_kg;
  for (std::size_t i = 0; i < m.size(); ++i)
    kinetic_J += 0.5 * m[i] *
                 (v + w.cross(s.positions_m[i] - car.centreOfMass_m()) + s.velocities_mps[i]).squaredNorm();
  return kinetic_J;
}

bool crushable(const World& world, EntityRef e) {
  return e.kind == EntityRef::Kind::Car || crushesBody(world.obstacleKind(e.index));
}

bool vegetation(const World& world, EntityRef e) {
  return e.kind == EntityRef::Kind::Obstacle && world.obstacleKind(e.index) == ObstacleKind::Vegetation;
}

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
  // The shell's share of the car's mass, spread over the points by the tetrahedral fan (its shape only:
  // the points hold shell_mass_fraction of the car); the chassis keeps the rest.
  deform::MassSplit masses = deform::distributeMass(dc->mesh, car.mass_kg);
  double points_kg = 0;
  for (double m : masses.point_mass_kg) points_kg += m;
  const double shell_kg = car.mass_kg * deformation.shell_mass_fraction;
  for (double& m : masses.point_mass_kg) m *= shell_kg / points_kg;
  masses.core_mass_kg = car.mass_kg - shell_kg;
  deform::BodyDescription description;
  description.material = deformation.material;
  description.max_deviation_m = deformation.max_deviation_m;
  description.anchored_columns = deformation.anchored_columns;
  const deform::Aabb bounds_m = deform::boundingBox(model.body);
  description.regions = placeMaterialMap(deformation.regions, deformation.material, bounds_m);
  dc->body_settings =
      std::make_shared<const deform::BodySettings>(deform::createBodySettings(dc->mesh, masses, description));
  deform::SolverParams params;
  params.substeps = static_cast<uint32_t>(deformation.substeps);
  params.iterations = static_cast<uint32_t>(deformation.iterations);
  params.damping_per_s = deformation.damping;
  params.yield_limited = deformation.yield_limited;
  // Crush: the shell's inertia is real, at full scale; Visual: the paper's scaled fictitious forces.
  params.inertial_scale = deformation.coupling == Coupling::Crush ? 1.0 : deformation.inertial_scale;
  dc->body = std::make_unique<deform::DeformableBody>(dc->body_settings, params);

  const CarId id = impl_->world.addCar(model, car, start);
  dc->id = id;
  Car& c = impl_->world.car(id);
  if (deformation.coupling == Coupling::Crush) {
    if (deformation.backstop == Backstop::ShrunkHull) {
      impl_->world.setCrushAllowance(id, deformation.crush_allowance_m);
    } else {
      std::vector<deform::Aabb> parts;
      for (const deform::Aabb& f : deformation.rigid_parts)
        parts.push_back(placeFractions(f, bounds_m, false));
      impl_->world.setRigidParts(id, parts);
    }
    // Crush: the shell's points are real mass, moving on their own and pulling on the chassis through
    // the spokes (its weight and inertia included), so the ODE chassis carries the rest of the car.
    Eigen::Matrix3d shell_inertia = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < masses.point_mass_kg.size(); ++i) {
      const Eigen::Vector3d r = dc->mesh.points_m[i] - c.centreOfMass_m();
      shell_inertia +=
          masses.point_mass_kg[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    c.carryShell(shell_kg, shell_inertia);
    dc->chassis_share_of_rotation = c.inertia_kg_m2().inverse() * c.chassisInertia_kg_m2();
  }
  dc->previous_velocity_mps = c.velocity_mps();
  dc->previous_omega_radps = c.angularVelocity_rad_s();
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
    kinetic_before.push_back(m.carKineticEnergy(*dc));
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
    taken_J -=
        (drag + car.mass_kg() * m.world.settings().gravity_mps2).dot(v_mid) * dt;  // whole car's weight
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

StepTimings Simulation::lastTimings() const {
  return impl_->timings;
}

uint64_t Simulation::stateHash() const {
  StateWriter out(true);
  saveState(out);
  return fnv1a(out.bytes().data(), out.bytes().size());
}

}  // namespace vehicle
