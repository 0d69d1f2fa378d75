// One deformable car's step in the crush coupling (simulation.hpp; DESIGN.md section 5): what it touches
// becomes deform's moving contacts, deform steps with the chassis as its heavy core, and the reaction goes
// to the chassis in the same step.
#include "simulation_impl.hpp"

#include <deform/masses.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vehicle {

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

bool Simulation::Impl::pairsWith(const DeformableCar& dc, EntityRef other) const {
  if (other.kind != EntityRef::Kind::Car || other.index >= index_of.size() || index_of[other.index] < 0)
    return false;
  return dc.settings.coupling == of(other.index).settings.coupling;
}

void Simulation::Impl::addApproaching(DeformableCar& dc) const {
  // ODE collides before it integrates: its contacts are where the car was when the step began, so an
  // obstacle the car reaches during the step would reach deform a step late, with the control points
  // already inside it, and their push-out would throw them back (energy from nowhere). Everything
  // crushable whose box (this step's, updateBoxes) comes within the step's travel of the points' box is
  // handed to deform now; its contacts are exact within the substeps, so one not reached does nothing.
  const Car& car = world.car(dc.id);
  const Box& mine = car_boxes[dc.id];
  double fastest_point_mps = 0;
  for (const Eigen::Vector3d& v : dc.body->state().velocities_mps)
    fastest_point_mps = std::max(fastest_point_mps, v.norm());
  const Eigen::Vector3d core_world_m = car.vehiclePose().toWorld(dc.body_settings->core_m);
  const EntityRef self{EntityRef::Kind::Car, dc.id};
  const Eigen::Vector3d self_mps = velocityOf(self, core_world_m);
  const Eigen::Vector3d self_radps = car.angularVelocity_rad_s();
  auto consider = [&](EntityRef other, const Box& box, const Eigen::Vector3d& other_mps,
                      const Eigen::Vector3d& other_radps) {
    // Visual: what a ghost is in stays in reach while the chassis bounces off it.
    const DeformableCar* other_car = visualCar(other);
    const double ghost_m = dc.ghost_offset_m.norm() + (other_car ? other_car->ghost_offset_m.norm() : 0.0);
    const double ghost_mps =
        dc.ghost_velocity_mps.norm() + (other_car ? other_car->ghost_velocity_mps.norm() : 0.0);
    const double closing_mps = (other_mps - self_mps).norm() +
                               (other_radps - self_radps).norm() * mine.halfDiagonal_m() + fastest_point_mps +
                               ghost_mps;
    if (mine.grown(closing_mps * world.fixedDt_s() + kApproachMargin_m + ghost_m).overlaps(box) &&
        std::find(dc.touching.begin(), dc.touching.end(), other) == dc.touching.end())
      dc.touching.push_back(other);
  };
  for (ObstacleId o = 0; o < world.obstacleCount(); ++o) {
    const EntityRef other{EntityRef::Kind::Obstacle, o};
    if (crushable(world, other, dc.settings.coupling))
      consider(other, obstacle_boxes[o], velocityOf(other, core_world_m), angularVelocityOf(other));
  }
  // Another car is within reach only if its box comes within the growth below of this one's. That growth
  // is at most C + w dt L, with w the fastest turn and L the distance from this core to the other's
  // centre, itself at most sqrt(3) times the boxes' gap plus two half-diagonals: so only boxes within
  // r = (C + 2 w dt R) / (1 - sqrt(3) w dt) can be, and only those are tested (the same cars, in the same
  // order, as testing all of them; all of them when the turn is too fast for the bound).
  const double dt = world.fixedDt_s();
  const double turn = std::sqrt(3.0) * fastest_turn_radps * dt;
  std::vector<uint32_t> candidates;
  if (turn < 0.5) {
    const double c_m =
        (fastest_car_mps + self_mps.norm() +
         (fastest_turn_radps + self_radps.norm()) * mine.halfDiagonal_m() + fastest_point_mps) *
            dt +
        kApproachMargin_m + dc.ghost_offset_m.norm() + dc.ghost_velocity_mps.norm() * dt + largest_ghost_m;
    const double reach_m = (c_m + 2.0 * fastest_turn_radps * dt * largest_half_diagonal_m) / (1.0 - turn);
    car_grid.near(mine.grown(1.01 * reach_m + 1e-6), candidates);
  } else {
    for (CarId c = 0; c < world.carCount(); ++c) candidates.push_back(c);
  }
  for (const uint32_t c : candidates) {  // velocityOf(car, core) and its turn, from car_motion
    if (c == dc.id) continue;
    const CarMotion& m = car_motion[c];
    consider({EntityRef::Kind::Car, c}, car_boxes[c],
             m.velocity_mps + m.omega_radps.cross(core_world_m - m.com_m), m.omega_radps);
  }
}

void Simulation::Impl::prepareCar(DeformableCar& dc) const {
  const Car& car = world.car(dc.id);
  dc.frame = car.vehiclePose();
  const Pose& frame = dc.frame;
  const Eigen::Quaterniond to_vehicle = frame.orientation.conjugate();
  const double dt = world.fixedDt_s();
  const std::vector<CarContact> contacts = world.carContacts(dc.id);
  const bool crush = dc.settings.coupling == Coupling::Crush;

  // What the car touches (not the ground, not ramps), each once: in ODE's contacts, or within reach of
  // the control points during this step.
  dc.touching.clear();
  for (const CarContact& c : contacts)
    if (crushable(world, c.other, dc.settings.coupling) &&
        std::find(dc.touching.begin(), dc.touching.end(), c.other) == dc.touching.end())
      dc.touching.push_back(c.other);
  dc.in_ode_contact = dc.touching.size();
  addApproaching(dc);
  // Another deformable car in the same coupling: the two bodies are stepped as one (deform's stepGroup,
  // Simulation::step), each meeting the other's surface as it deforms; not a shape here.
  dc.partners.clear();
  dc.partner_in_ode.clear();
  {
    std::size_t kept = 0, kept_in_ode = 0;
    for (std::size_t k = 0; k < dc.touching.size(); ++k) {
      const EntityRef other = dc.touching[k];
      if (pairsWith(dc, other)) {
        dc.partners.push_back(other.index);
        dc.partner_in_ode.push_back(k < dc.in_ode_contact ? 1 : 0);
        continue;
      }
      dc.touching[kept++] = other;
      if (k < dc.in_ode_contact) ++kept_in_ode;
    }
    dc.touching.resize(kept);
    dc.in_ode_contact = kept_in_ode;
  }

  // The obstacles where they are at the end of the step (vehicle frame), with their motion relative to
  // the chassis (the velocity of their point at the core, and their turn): deform moves them along it
  // through its substeps, and its friction holds a point to their surface. A wall seen from a car that
  // pitches turns the other way.
  const Eigen::Vector3d core_world_m = frame.position_m + frame.orientation * dc.body_settings->core_m;
  const EntityRef self{EntityRef::Kind::Car, dc.id};
  // Visual: ODE's rigid contact stopped the chassis; the body meets what it hit where the car would be
  // without that contact (the ghost, advanceGhost).
  dc.frame_velocity_mps = to_vehicle * velocityOf(self, core_world_m);
  dc.frame_omega_radps = to_vehicle * car.angularVelocity_rad_s();
  dc.inputs = {};
  deform::StepInputs& inputs = dc.inputs;
  inputs.contact_friction = dc.settings.contact_friction;
  dc.shapes.clear();
  for (const EntityRef& other : dc.touching) {
    const ObstacleShape world_shape = worldShapeOf(other);
    ObstacleShape local = transformShape(world_shape, frame);
    // A free body (a box, a tree, a rigid or visual car) takes the body's reaction at its centre of mass
    // (finishCar, centreOf), so deform moves it as a particle: at its centre's velocity, without its turn.
    // With the velocity of its material at the contact, a tree held at its foot by the ground was pushed at
    // the slower speed of its lower trunk while the push sped up its centre: it left faster than the car, 4.4
    // kJ created at 10 km/h.
    const double w_other = crush ? world.inverseMass_per_kg(other) : 0.0;
    const bool free_body = w_other > 0;
    Eigen::Vector3d relative_mps =
        to_vehicle *
        ((free_body ? velocityOf(other) : velocityOf(other, core_world_m)) - velocityOf(self, core_world_m));
    if (!crush) {  // met by the ghost (another visual car is a partner, not a shape)
      local = transformShape(local, {dc.ghost_offset_m, {1, 0, 0, 0}});
      relative_mps -= dc.ghost_velocity_mps;
    }
    const Eigen::Vector3d relative_radps =
        to_vehicle *
        ((free_body ? Eigen::Vector3d::Zero() : angularVelocityOf(other)) - car.angularVelocity_rad_s());
    // Sweep away from the car, against the contact normals. A point can be as deep as the deepest contact
    // at the start of the step plus the step's closing travel; twice that keeps the near face the nearest.
    Eigen::Vector3d normal{0, 0, 0};
    double deepest_m = 0;
    for (const CarContact& c : contacts)
      if (c.other == other) {
        normal += c.normal;
        deepest_m = std::max(deepest_m, c.depth_m);
      }
    // Not yet in ODE's contacts (addApproaching): if it closes on the car, it comes along its relative
    // motion; one moving away is not swept (the sweep would reach back into the car).
    const bool closing_in = relative_mps.dot(dc.body_settings->core_m - interiorPoint(local)) > 0;
    if (normal.norm() <= 1e-12 && closing_in && relative_mps.norm() > 1e-9)
      normal = relative_mps.normalized();
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
    inputs.contact_angular_velocity_radps.push_back(relative_radps);
    // Crush: a free obstacle (a box, a tree, a rigid car, a car in the visual coupling) is pushed inside
    // the substeps by its mass, and takes the body's reaction below. (A crush car's soft hull has no ODE
    // contact with a visual car's hull: taken as immovable, a visual car drove into the body as a piston
    // and gave it momentum nobody lost.) Another crush car is a partner, not here. Visual: what the
    // chassis hits moves by ODE's contact alone.
    inputs.contact_inverse_mass_per_kg.push_back(w_other);
    inputs.contact_keys.push_back(w_other > 0 ? freeObstacleKey(other) : 0);
    // What holds it (ODE's contacts with the ground and static things this step), out of them.
    std::vector<Eigen::Vector3d> held;
    if (w_other > 0)
      for (const ContactPoint& c : world.contacts()) {
        const bool is_a = c.a == other, is_b = c.b == other;
        if ((is_a || is_b) && world.inverseMass_per_kg(is_a ? c.b : c.a) == 0)
          held.push_back(to_vehicle * (is_a ? c.normal : Eigen::Vector3d(-c.normal)));
      }
    inputs.contact_held_normals.push_back(std::move(held));
  }
  inputs.contacts = dc.shapes.shapes();
  inputs.surface_contact = dc.shapes.surfaceFlags();
  inputs.frame_to_world = frame.orientation.toRotationMatrix();
  // Crush: the core is the chassis, a heavy particle inside deform's substeps; what the body hands it is
  // handed to ODE below, in this step. Visual: the chassis is rigid to what it hits (ODE's contact).
  if (crush) {
    inputs.core_mass_kg = car.chassisMass_kg();
    // The rigid stop at the caps turns chassis and shell together (finishCar's share of the moment).
    inputs.core_inverse_inertia_per_kg_m2 = car.inertia_kg_m2().inverse();
    inputs.core_centre_of_mass_m = car.centreOfMass_m();
  }

  // The chassis's motion over ODE's step (its forces only: the body's reaction of the last step moved the
  // points with it) is deform's frame: the points feel the inertial load of ODE's acceleration of the
  // chassis alone, and their reaction shares it with the shell once. In translation deform's core is a
  // free particle of the chassis's mass that the points pull along (the whole car's acceleration
  // M_c / M of ODE's comes out of the substeps); in rotation the core does not turn inside deform, so
  // finishCar shares the moment, I_c (I_c + I_s)^-1. Feeding the whole car's acceleration as well shared
  // it twice: a braking car's momentum changed 8 % faster than its tyres' impulse (car_to_car's struck
  // car left 20 % of its impact energy unexplained), and pole_side's sliding sedan gained 2.5 km/h in
  // its first 10 ms (docs/CRASH_CALIBRATION.md, "Energy account"). Visual: scaled by inertial_scale.
  if (crush || dc.settings.inertial_scale > 0) {
    const Eigen::Vector3d acceleration = (car.velocity_mps() - dc.previous_velocity_mps) / dt;
    inputs.chassis.acceleration_mps2 = to_vehicle * acceleration;
    inputs.chassis.angular_velocity_radps = to_vehicle * car.angularVelocity_rad_s();
    inputs.chassis.angular_acceleration_radps2 =
        to_vehicle * ((car.angularVelocity_rad_s() - dc.previous_omega_radps) / dt);
    inputs.chassis.gravity_mps2 = to_vehicle * world.settings().gravity_mps2;
  }

  dc.plastic_before_step_J = dc.body->state().plastic_work_J;
  dc.contact_loss_before_step_J = dc.contact_loss_J;
  if (!dc.metrics.impacted) dc.elastic_before_step_J = dc.elastic_after_step_J;
}

const DeformableCar* Simulation::Impl::visualCar(EntityRef e) const {
  if (e.kind != EntityRef::Kind::Car || e.index >= index_of.size() || index_of[e.index] < 0) return nullptr;
  const DeformableCar& other = of(e.index);
  return other.settings.coupling == Coupling::Visual ? &other : nullptr;
}

Eigen::Vector3d Simulation::Impl::onTheGround(const DeformableCar& dc,
                                              const Eigen::Vector3d& impulse_Ns) const {
  // The ghost stands on its wheels as the car does: the ground takes what would lift it or press it down
  // (with that freedom two ghosts head-on drifted apart vertically, one car denting 8 % more).
  const Eigen::Vector3d up =
      world.car(dc.id).vehiclePose().orientation.conjugate() * Eigen::Vector3d::UnitZ();
  return impulse_Ns - impulse_Ns.dot(up) * up;
}

void Simulation::Impl::advanceGhost(DeformableCar& dc) const {
  // The velocity ODE's contacts with what the car crushes took from the chassis stays with the ghost.
  if (dc.settings.coupling != Coupling::Visual) return;
  Eigen::Vector3d taken_Ns{0, 0, 0};
  dc.ghost_in_ode_contact = false;
  dc.ghost_contact_normal.setZero();
  for (const CarContact& c : world.carContacts(dc.id))
    if (crushable(world, c.other, dc.settings.coupling)) {
      taken_Ns += c.impulse_N_s;
      dc.ghost_in_ode_contact = true;
      dc.ghost_contact_normal += c.normal;
    }
  dc.ghost_velocity_mps -= onTheGround(dc, taken_Ns) / world.car(dc.id).mass_kg();
  dc.ghost_offset_m += dc.ghost_velocity_mps * world.fixedDt_s();  // where it is at the end of this step
}

void Simulation::Impl::updateGhost(DeformableCar& dc) const {
  // The body's contact impulses slow the ghost as the crush coupling's slow the chassis: the whole car's
  // momentum, which ODE's contact took from the chassis, goes into the dent.
  const Eigen::Vector3d pushed_Ns = dc.report.contact_impulse_Ns;  // what it touches, and its partners
  const Car& car = world.car(dc.id);
  dc.ghost_velocity_mps += onTheGround(dc, pushed_Ns) / car.mass_kg();
  if (pushed_Ns.squaredNorm() > 0) return;
  // Nothing pushed the body this step: the ghost is not inside what it hit. Without ODE's contact either
  // (with an obstacle or another car), the impact is over; with it (a car resting against a wall), the
  // ghost does not draw back behind the chassis along the contact normal, so that the next push meets the
  // obstacle where it stands.
  if (!dc.ghost_in_ode_contact) {
    dc.ghost_velocity_mps.setZero();
    dc.ghost_offset_m.setZero();
    return;
  }
  if (!(dc.ghost_contact_normal.norm() > 1e-12)) return;
  const Eigen::Vector3d normal = dc.ghost_contact_normal.normalized();
  dc.ghost_offset_m -= std::max(0.0, dc.ghost_offset_m.dot(normal)) * normal;
  dc.ghost_velocity_mps -= std::max(0.0, dc.ghost_velocity_mps.dot(normal)) * normal;
}

void Simulation::Impl::solveCar(DeformableCar& dc) const {
  dc.report = dc.body->step(dc.inputs, world.fixedDt_s());
  if (!dc.report.asleep) dc.elastic_after_step_J = dc.body->carriedElasticEnergy_J();
  ++(dc.report.asleep ? dc.deform_steps_skipped : dc.deform_steps);
}

void Simulation::Impl::finishCar(DeformableCar& dc) {
  Car& car = world.car(dc.id);
  const Pose& frame = dc.frame;
  const double dt = world.fixedDt_s();
  const bool crush = dc.settings.coupling == Coupling::Crush;
  const deform::StepReport& report = dc.report;
  dc.damping_loss_J += report.damping_loss_J;
  dc.contact_work_J += report.contact_work_J;
  dc.inertial_work_J += report.inertial_work_J;
  // The obstacles' work in the world: deform's is in the frame of the chassis as the step began. Visual:
  // the chassis's core is rigid (the body's impulses never reach it) and the obstacles move against the
  // ghost, so deform's own figure is the work they did on the body, the energy the ghost brought to the
  // dent; ODE's rigid contact took the same energy from the chassis (other work).
  const double obstacle_work_J = crush ? report.obstacle_work_J +
                                             report.contact_impulse_Ns.dot(dc.frame_velocity_mps) +
                                             report.contact_moment_Nms.dot(dc.frame_omega_radps)
                                       : report.obstacle_work_J;
  if (std::isfinite(obstacle_work_J)) dc.obstacle_work_J += obstacle_work_J;
  dc.contact_loss_J += report.contact_loss_J;
  dc.hit.assign(dc.touching.begin(), dc.touching.begin() + static_cast<std::ptrdiff_t>(dc.in_ode_contact));
  for (std::size_t k = 0; k < dc.partners.size(); ++k)  // another car's body, in ODE's contacts or pushed
    if (dc.partner_in_ode[k] || (k < dc.partner_pushed.size() && dc.partner_pushed[k]))
      dc.hit.push_back({EntityRef::Kind::Car, dc.partners[k]});
  for (std::size_t k = dc.in_ode_contact; k < dc.touching.size(); ++k)
    if (k < report.contact_impulse_per_obstacle_Ns.size() &&
        report.contact_impulse_per_obstacle_Ns[k].squaredNorm() > 0)
      dc.hit.push_back(dc.touching[k]);

  // Reaction, equal and opposite in this step: the momentum the body handed its core goes to the chassis
  // (and the core's travel within the step to its position); the momentum the obstacles gave the points
  // goes back to a free obstacle (a pushed box), at the contact points' centre.
  dc.step_crush_work_J = 0;
  // A body that diverged (its metrics say so, with where and when) hands ODE nothing: ODE aborts on a NaN.
  const bool finite = report.core_impulse_Ns.allFinite() && report.core_angular_impulse_Nms.allFinite() &&
                      report.core_displacement_m.allFinite();
  if (crush && finite) {
    const double kinetic_before_J = kineticEnergy(car);
    // The moment turns chassis and shell together: the points live in the chassis's frame, so the shell
    // turns with it rigidly and takes its share, I_s I^-1, of the angular momentum.
    const Eigen::Vector3d lever = dc.body_settings->core_m - car.centreOfMass_m();
    const Eigen::Vector3d moment = dc.chassis_share_of_rotation.transpose() *
                                   (lever.cross(report.core_impulse_Ns) + report.core_angular_impulse_Nms);
    world.applyImpulse({EntityRef::Kind::Car, dc.id}, frame.orientation * report.core_impulse_Ns,
                       car.bodyPose().position_m, frame.orientation * moment);
    world.shiftCar(dc.id, frame.orientation * report.core_displacement_m);
    dc.step_crush_work_J = kinetic_before_J - kineticEnergy(car);
    // A free obstacle (deform moved it as a particle inside the substeps, prepareCar) takes the velocity
    // change deform gave it, and goes where its push took it: minus the impulse it gave the body, less what
    // holds it takes (a wall it is pinched against). ODE then carries it on. Static obstacles and another
    // deformable car (which takes its share through its own body) have no inverse mass here.
    for (std::size_t k = 0; k < dc.touching.size(); ++k) {  // one contact shape per touched entity
      const double w_other = dc.inputs.contact_inverse_mass_per_kg[k];
      if (!(w_other > 0)) continue;
      const EntityRef& other = dc.touching[k];
      const Eigen::Vector3d impulse =
          frame.orientation * Eigen::Vector3d(report.obstacle_velocity_change_mps[k] / w_other);
      if (impulse.squaredNorm() > 0 && impulse.allFinite())
        // A car's at its centre of mass, as deform moved it (its hull's interior point is not: a visual
        // car turned by it created 34.6 % of a three-car run, seed 11 scene 614). An obstacle's at its
        // shape's centre as the step found it: its centre of mass after another car's shift this step
        // made a box pinched between two cars depend on their order (20.0 against 19.6 kJ).
        world.applyImpulse(
            other, impulse,
            other.kind == EntityRef::Kind::Car ? centreOf(other) : interiorPoint(worldShapeOf(other)));
      const Eigen::Vector3d moved = report.obstacle_displacement_m[k];
      if (moved.squaredNorm() > 0 && moved.allFinite()) world.shift(other, frame.orientation * moved);
    }
  }
  if (!crush && finite) updateGhost(dc);
  dc.previous_velocity_mps = car.velocity_mps();
  dc.previous_omega_radps = car.angularVelocity_rad_s();

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
      dc.partners.empty() && report.max_speed_mps < 0.05) {
    const std::size_t n = std::max<std::size_t>(4, car.settings().collision_points);
    const deform::ControlMesh dented = collisionHull(dc.body->state().positions_m, n, "dented body");
    // A body crushed through its own centre of mass (a small car, a deep dent) keeps its old hull: ODE's
    // convex geom needs the centre inside (its planes' offsets positive), or it warns and mis-collides.
    if (enclosesWithMargin(dented, dc.body_settings->core_m, 0.01)) {
      car.setCollisionHull(dented);
      if (dc.settings.backstop == Backstop::ShrunkHull) {  // the stroke left; rigid parts stay where they are
        const double used = deform::maxDeviation(*dc.body_settings, dc.body->state());
        world.setCrushAllowance(dc.id, std::max(0.0, dc.settings.crush_allowance_m - used));
      }
    }
    dc.hull_dirty = false;
  }
}
}  // namespace vehicle
