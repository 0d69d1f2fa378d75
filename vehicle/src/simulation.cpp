// A World with deformable cars and the crush coupling (simulation.hpp; DESIGN.md section 5): the API.
// The step is simulation_step.cpp, one car's deformation crush_coupling.cpp, its metrics
// crash_metrics_update.cpp, the shared builds car_build.cpp.
#include "input_checks.hpp"
#include "simulation_impl.hpp"

#include <deform/error.hpp>
#include <deform/masses.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vehicle {
namespace {

/// The deformation settings' members are named in messages by their path in a scene file.
void requireDeformation(bool ok, const char* member, const std::string& rule, double value) {
  detail::require(ok, std::string("vehicle.deformation.") + member, rule, value);
}

}  // namespace

// The default (longest_contact_substep_s unset, 0): 0.5 ms from 250 control points up, none below.
// Measured at 120 Hz (4 substeps of 2.1 ms), unexplained energy against the car's initial kinetic energy:
// traffic's pile of four cars, the runner at 1,000 points -2150 % -> -8 %, at 250 points -488 % -> -5 %;
// east4 against its tree at 250 points -17 % -> +0.8 %. At 60 points the shorter substeps made the pile worse
// (-11 % -> -46 %), so the coarse levels keep their own (docs/CRASH_CALIBRATION.md, "Two cars, one
// solve").
double contactSubstep_s(const DeformationSettings& s, std::size_t control_points) {
  constexpr std::size_t kFinestWithout = 250;
  constexpr double kLongestFine_s = 0.5e-3;
  if (s.longest_contact_substep_s > 0) return s.longest_contact_substep_s;
  return control_points >= kFinestWithout ? kLongestFine_s : HUGE_VAL;
}

double contactSubstep_s(const DeformationSettings& s) {
  return contactSubstep_s(s, s.control_points);
}

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

bool crushable(const World& world, EntityRef e, Coupling coupling) {
  if (e.kind == EntityRef::Kind::Car) return true;
  const ObstacleKind kind = world.obstacleKind(e.index);
  // The visual coupling's ghost meets what ODE's rigid hull moves: a plant it knocks over and then rides
  // over is met where the car would be without that contact, and was pumped into the body (post_bumps:
  // 796 kJ of plastic work from 12.7 kJ). Its body is left to the crush coupling.
  if (coupling == Coupling::Visual && kind == ObstacleKind::Vegetation) return false;
  return crushesBody(kind);
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
  requireDeformation(s.control_points >= 4 && s.control_points <= 5000, "control_points",
                     "must be in [4, 5000]", static_cast<double>(s.control_points));
  requireDeformation(std::isfinite(s.alpha) && s.alpha > 0, "alpha", "must be finite and positive", s.alpha);
  requireDeformation(s.substeps >= 1 && s.substeps <= 1000, "substeps", "must be in [1, 1000]", s.substeps);
  requireDeformation(s.iterations >= 1 && s.iterations <= 1000, "iterations", "must be in [1, 1000]",
                     s.iterations);
  requireDeformation(std::isfinite(s.max_deviation_m) && s.max_deviation_m > 0, "max_deviation_m",
                     "must be finite and positive", s.max_deviation_m);
  deform::checkMaterial(s.material, "vehicle.deformation.material");
  requireDeformation(
      std::isfinite(s.shell_mass_fraction) && s.shell_mass_fraction > 0 && s.shell_mass_fraction <= 1,
      "shell_mass_fraction", "must be in (0, 1]", s.shell_mass_fraction);
  requireDeformation(std::isfinite(s.damping) && s.damping >= 0, "damping", "must be finite and >= 0",
                     s.damping);
  requireDeformation(std::isfinite(s.contact_friction) && s.contact_friction >= 0, "contact_friction",
                     "must be finite and >= 0", s.contact_friction);
  requireDeformation(s.max_depenetration_mps > 0, "max_depenetration_mps", "must be > 0 (infinite: no cap)",
                     s.max_depenetration_mps);
  requireDeformation(s.longest_contact_substep_s >= 0, "longest_contact_substep_s",
                     "must be >= 0 (0: by the control points)", s.longest_contact_substep_s);
  requireDeformation(std::isfinite(s.crush_allowance_m) && s.crush_allowance_m >= 0, "crush_allowance_m",
                     "must be finite and >= 0", s.crush_allowance_m);
  requireDeformation(std::isfinite(s.inertial_scale) && s.inertial_scale >= 0, "inertial_scale",
                     "must be finite and >= 0", s.inertial_scale);
  requireDeformation(std::isfinite(s.contact_edge_m) && s.contact_edge_m > 0, "contact_edge_m",
                     "must be finite and > 0", s.contact_edge_m);
  requireDeformation(s.max_control_points >= s.control_points && s.max_control_points <= 100000,
                     "max_control_points", "must be in [control_points, 100000]",
                     static_cast<double>(s.max_control_points));
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
  dc->build = impl_->builds.get(model, car, deformation);
  dc->body_settings = dc->build->body_settings;
  deform::SolverParams params;
  params.substeps = static_cast<uint32_t>(deformation.substeps);
  params.iterations = static_cast<uint32_t>(deformation.iterations);
  params.damping_per_s = deformation.damping;
  params.max_depenetration_mps = deformation.max_depenetration_mps;
  params.longest_contact_substep_s = contactSubstep_s(deformation);
  params.yield_limited = deformation.yield_limited;
  // Crush: the shell's inertia is real, at full scale; Visual: the paper's scaled fictitious forces.
  params.inertial_scale = deformation.coupling == Coupling::Crush ? 1.0 : deformation.inertial_scale;
  dc->body = std::make_unique<deform::DeformableBody>(dc->body_settings, params);

  const CarId id = impl_->world.addCar(dc->build->collision_hull, wheelsFromModel(car, model), car, start);
  const deform::Aabb& bounds_m = dc->build->bounds_m;
  const deform::MassSplit& masses = dc->build->masses;
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
      const Eigen::Vector3d r = dc->build->control_mesh.points_m[i] - c.centreOfMass_m();
      shell_inertia +=
          masses.point_mass_kg[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    c.carryShell(dc->build->shell_mass_kg, shell_inertia);
    dc->chassis_share_of_rotation = c.inertia_kg_m2().inverse() * c.chassisInertia_kg_m2();
  }
  dc->previous_velocity_mps = c.velocity_mps();
  dc->previous_omega_radps = c.angularVelocity_rad_s();
  if (impl_->index_of.size() <= id) impl_->index_of.resize(id + 1, -1);
  impl_->index_of[id] = static_cast<int>(impl_->cars.size());
  impl_->cars.push_back(std::move(dc));
  return id;
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
  return impl_->of(car).build->control_mesh;
}

const DeformationSettings& Simulation::deformationSettings(CarId car) const {
  return impl_->of(car).settings;
}

const deform::DeformableBody& Simulation::body(CarId car) const {
  return *impl_->of(car).body;
}

Simulation::DeformCounts Simulation::deformCounts(CarId car) const {
  const DeformableCar& dc = impl_->of(car);
  return {dc.deform_steps, dc.deform_steps_skipped};
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
