// The energy watch (simulation_impl.hpp, EnergyWatch; DESIGN.md section 7): no run creates energy or
// throws a car higher than its speed allows and still reports success.
#include "simulation_impl.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vehicle {
namespace {

/// The wheels' spin energy [J]: the start gives them the car's speed, and a tyre hands it to the chassis.
double wheelEnergy_J(const Car& car) {
  double energy_J = 0;
  const std::vector<WheelState>& wheels = car.wheels();
  const std::vector<WheelSettings>& settings = car.wheelSettings();
  for (std::size_t i = 0; i < wheels.size() && i < settings.size(); ++i)
    energy_J += 0.5 * settings[i].inertia_kg_m2 * wheels[i].tyre.spin_rad_s * wheels[i].tyre.spin_rad_s;
  return energy_J;
}

/// The engines' work on the wheels over the last step [J], at the spin the step ended with.
double driveWork_J(const Car& car, double dt_s) {
  double work_J = 0;
  for (const WheelState& w : car.wheels()) work_J += w.drive_torque_Nm * w.tyre.spin_rad_s * dt_s;
  return work_J;
}

const char* kindName(ObstacleKind kind) {
  switch (kind) {
    case ObstacleKind::Ground:
      return "ground";
    case ObstacleKind::Wall:
      return "wall";
    case ObstacleKind::Post:
      return "post";
    case ObstacleKind::Vegetation:
      return "vegetation";
    case ObstacleKind::Ramp:
      return "ramp";
    case ObstacleKind::ConvexMesh:
      return "convex mesh";
  }
  return "obstacle";
}

}  // namespace

void Simulation::Impl::wholeCarCentre(CarId c, Eigen::Vector3d& position_m,
                                      Eigen::Vector3d& velocity_mps) const {
  const Car& car = world.car(c);
  position_m = car.bodyPose().position_m;
  velocity_mps = car.velocity_mps();
  if (c >= index_of.size() || index_of[c] < 0 || of(c).settings.coupling != Coupling::Crush) return;
  // In the crush coupling the shell's points are mass of their own: the body's reaction moves the chassis
  // against them, and only the two together fly as a thrown body does.
  const DeformableCar& dc = of(c);
  const Pose pose = car.vehiclePose();
  const Eigen::Vector3d omega = car.angularVelocity_rad_s();
  const deform::BodyState& s = dc.body->state();
  const std::vector<double>& m = dc.body_settings->mass_kg;
  double mass_kg = car.chassisMass_kg();
  Eigen::Vector3d moment = mass_kg * position_m, momentum = mass_kg * velocity_mps;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const Eigen::Vector3d p = pose.toWorld(s.positions_m[i]);
    moment += m[i] * p;
    momentum += m[i] * (car.velocity_mps() + omega.cross(p - car.bodyPose().position_m) +
                        pose.orientation * s.velocities_mps[i]);
    mass_kg += m[i];
  }
  position_m = moment / mass_kg;
  velocity_mps = momentum / mass_kg;
}

double Simulation::Impl::watchedEnergy_J(std::vector<double>& per_car_J, double& kinetic_J,
                                         double& potential_J) const {
  const Eigen::Vector3d g = world.settings().gravity_mps2;
  kinetic_J = 0;
  potential_J = 0;
  double booked_J = 0;
  per_car_J.assign(world.carCount(), 0.0);
  for (CarId c = 0; c < world.carCount(); ++c) {
    const Car& car = world.car(c);
    const bool deforms = c < index_of.size() && index_of[c] >= 0;
    const double kinetic = (deforms ? carKineticEnergy(of(c)) : kineticEnergy(car)) + wheelEnergy_J(car);
    const double potential = -car.mass_kg() * g.dot(car.bodyPose().position_m);
    // What the crush coupling's body took from the car's motion. (A visual car's body dents with the
    // ghost's energy, which ODE's rigid contact took from the chassis: not booked twice.)
    double booked = 0;
    if (deforms && of(c).settings.coupling == Coupling::Crush) {
      const DeformableCar& dc = of(c);
      booked = dc.body->state().plastic_work_J + dc.damping_loss_J + dc.contact_loss_J -
               dc.link_loss_counted_twice_J;
    }
    per_car_J[c] = kinetic + potential + booked;
    kinetic_J += kinetic;
    potential_J += potential;
    booked_J += booked;
  }
  for (ObstacleId o = 0; o < world.obstacleCount(); ++o) {
    if (!world.obstacleIsDynamic(o)) continue;
    const double w = world.inverseMass_per_kg({EntityRef::Kind::Obstacle, o});
    kinetic_J += world.obstacleKineticEnergy_J(o);
    if (w > 0) potential_J -= g.dot(world.obstaclePose(o).position_m) / w;
  }
  return kinetic_J + potential_J + booked_J;
}

void Simulation::Impl::startWatch() {
  std::vector<double> per_car;
  double kinetic = 0, potential = 0;
  watch.initial_J = watchedEnergy_J(per_car, kinetic, potential);
  watch.initial_kinetic_J = kinetic;
  watch.initial_potential_J = potential;
  watch.lowest_potential_J = potential;
  watch.car_energy_J = per_car;
  watch.total_mass_kg = 0;
  for (CarId c = 0; c < world.carCount(); ++c) watch.total_mass_kg += world.car(c).mass_kg();
  for (ObstacleId o = 0; o < world.obstacleCount(); ++o) {
    const double w =
        world.obstacleIsDynamic(o) ? world.inverseMass_per_kg({EntityRef::Kind::Obstacle, o}) : 0;
    if (w > 0) watch.total_mass_kg += 1.0 / w;
  }
  watch.airborne.assign(world.carCount(), 0);
  watch.apex_m.assign(world.carCount(), 0.0);
  watch.started = true;
}

void Simulation::Impl::checkWatch() {
  // A car added since the watch started brings energy of its own: the watch starts again from here.
  if (watch.car_energy_J.size() != world.carCount()) {
    startWatch();
    return;
  }
  const double dt = world.fixedDt_s();
  for (CarId c = 0; c < world.carCount(); ++c) watch.drive_work_J += driveWork_J(world.car(c), dt);
  std::vector<double> per_car;
  double kinetic = 0, potential = 0;
  const double energy_J = watchedEnergy_J(per_car, kinetic, potential);
  watch.lowest_potential_J = std::min(watch.lowest_potential_J, potential);
  const double g = world.settings().gravity_mps2.norm();
  const double through_J = watch.through_J = watch.initial_kinetic_J + std::max(0.0, watch.drive_work_J) +
                                             (watch.initial_potential_J - watch.lowest_potential_J);
  const double created_J = energy_J - watch.initial_J - watch.drive_work_J;
  const double allowed_J =
      EnergyWatch::kTolerance * through_J + EnergyWatch::kFloorLift_m * watch.total_mass_kg * g;
  if (created_J > watch.largest_created_J) {
    watch.largest_created_J = created_J;
    watch.largest_created_share = through_J > 0 ? created_J / through_J : 0.0;
  }
  // The car whose energy rose most this step takes the blame.
  CarId blamed = 0;
  double rise_J = -1e300;
  for (CarId c = 0; c < world.carCount() && c < watch.car_energy_J.size(); ++c)
    if (per_car[c] - watch.car_energy_J[c] > rise_J && index_of.size() > c && index_of[c] >= 0) {
      rise_J = per_car[c] - watch.car_energy_J[c];
      blamed = c;
    }
  watch.car_energy_J = per_car;

  auto mark = [&](CarId c, const std::string& what) {
    if (c >= index_of.size() || index_of[c] < 0) {  // a rigid car: the first deformable one reports it
      if (cars.empty()) return;
      c = cars.front()->id;
    }
    DeformableCar& dc = of(c);
    if (dc.metrics.diverged) return;
    std::string touching;
    for (const EntityRef& e : dc.hit.empty() ? dc.touching : dc.hit) {
      touching += touching.empty() ? ", touching " : " and ";
      touching += e.kind == EntityRef::Kind::Car ? "car " + std::to_string(e.index)
                                                 : std::string(kindName(world.obstacleKind(e.index))) +
                                                       " (obstacle " + std::to_string(e.index) + ")";
    }
    dc.metrics.diverged = true;
    dc.metrics.diverged_at_s = world.time_s();
    dc.metrics.diverged_what = what + " in step " + std::to_string(world.stepCount()) + touching;
  };
  bool any_diverged = false;
  for (const auto& dc : cars) any_diverged = any_diverged || dc->metrics.diverged;
  if (!any_diverged && created_J > allowed_J) {
    char what[256];
    std::snprintf(
        what, sizeof what,
        "energy created: %.4g kJ, past the %.4g kJ allowed (%.0f %% of the %.4g kJ through the run)",
        created_J / 1e3, allowed_J / 1e3, EnergyWatch::kTolerance * 100, through_J / 1e3);
    mark(blamed, what);
    any_diverged = true;
  }

  // Ballistic flight: a car touching nothing (no wheel, no ODE contact, no contact of its body) rises no
  // higher than its upward speed when it left, v^2 / 2g.
  if (!(g > 0)) return;
  const Eigen::Vector3d up = -world.settings().gravity_mps2 / g;
  std::vector<uint8_t> touches(world.carCount(), 0);
  for (const ContactPoint& contact : world.contacts())
    for (const EntityRef& e : {contact.a, contact.b})
      if (e.kind == EntityRef::Kind::Car && e.index < touches.size()) touches[e.index] = 1;
  for (const auto& dc : cars)
    if (dc->report.contact_points > 0 || !dc->partners.empty()) touches[dc->id] = 1;
  for (CarId c = 0; c < world.carCount(); ++c) {
    for (const WheelState& w : world.car(c).wheels()) touches[c] = touches[c] || w.in_contact;
    if (touches[c]) {
      watch.airborne[c] = 0;
      continue;
    }
    Eigen::Vector3d centre_m, centre_mps;
    wholeCarCentre(c, centre_m, centre_mps);
    const double height_m = up.dot(centre_m);
    if (!watch.airborne[c]) {
      const double rising_mps = std::max(0.0, up.dot(centre_mps));
      watch.apex_m[c] = height_m + rising_mps * rising_mps / (2 * g) + EnergyWatch::kApexSlack_m;
      watch.airborne[c] = 1;
      continue;
    }
    if (!any_diverged && height_m > watch.apex_m[c]) {
      char what[192];
      std::snprintf(what, sizeof what,
                    "car %u's centre of mass rose to %.3f m, past its ballistic bound %.3f m", c, height_m,
                    watch.apex_m[c]);
      mark(c, what);
      any_diverged = true;
    }
  }
}

Simulation::EnergyWatchReport Simulation::energyWatch() const {
  const EnergyWatch& w = impl_->watch;
  return {w.largest_created_J, w.largest_created_share, w.through_J, w.drive_work_J};
}

}  // namespace vehicle
