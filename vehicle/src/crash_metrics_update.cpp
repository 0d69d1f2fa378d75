// What a run did to one deformable car (simulation.hpp, CrashMetrics): impact, rebound, crush profile,
// energy terms, divergence, updated after every step.
#include "segment_meets.hpp"
#include "simulation_impl.hpp"

#include <algorithm>
#include <cmath>

namespace vehicle {

void Simulation::Impl::updateMetrics(DeformableCar& dc, const Eigen::Vector3d& position_before,
                                     const Eigen::Vector3d& velocity_before, double kinetic_before) {
  const Car& car = world.car(dc.id);
  CrashMetrics& mt = dc.metrics;
  const deform::BodyState& s = dc.body->state();

  // Divergence (MuJoCo-style): non-finite or beyond 1e10 anywhere. A body that slept through the step
  // has the points it had after the step it fell asleep in, which were checked then (here and below).
  const bool points_moved = !dc.report.asleep;
  auto bad = [](const Eigen::Vector3d& v) { return !v.allFinite() || v.cwiseAbs().maxCoeff() > 1e10; };
  if (!mt.diverged) {
    for (std::size_t i = 0; points_moved && i < s.positions_m.size() && mt.diverged_what.empty(); ++i)
      if (bad(s.positions_m[i])) mt.diverged_what = "control point " + std::to_string(i);
    if (mt.diverged_what.empty() && (bad(car.bodyPose().position_m) || bad(car.velocity_mps())))
      mt.diverged_what = "chassis";
    mt.diverged = !mt.diverged_what.empty();
    if (mt.diverged) mt.diverged_at_s = world.time_s();
  }

  if (!mt.impacted && !dc.hit.empty()) {
    // First impact with the first thing hit: velocities before the step, positions now.
    const EntityRef other = dc.hit.front();
    mt.impacted = true;
    dc.impact_other = other;
    dc.impact_relative_velocity_mps = velocity_before - velocityBefore(other);
    dc.impact_com_m = car.bodyPose().position_m;
    dc.impact_other_m = interiorPoint(worldShapeOf(other));
    dc.impact_normal_sum.setZero();
    dc.impact_steps = 0;
    mt.energy.kinetic_initial_J = kinetic_before;
    dc.elastic_at_impact_J = dc.elastic_before_step_J;
    dc.contact_loss_at_impact_J = dc.contact_loss_before_step_J;
    dc.plastic_at_impact_J = dc.plastic_before_step_J;  // this step's plastic work counts
    dc.damping_at_impact_J = dc.damping_loss_J;
    dc.contact_work_at_impact_J = dc.contact_work_J;
    dc.inertial_work_at_impact_J = dc.inertial_work_J;
    dc.obstacle_work_at_impact_J = dc.obstacle_work_J;
  }
  // The impact normal: the depth-weighted normals of the contacts with what was hit over the first 10 ms
  // (the very first contact of two rounded fronts can have any normal).
  const int settle_steps = std::max(1, static_cast<int>(std::lround(0.01 / world.fixedDt_s())));
  if (mt.impacted && dc.impact_steps < settle_steps) {
    ++dc.impact_steps;
    for (const CarContact& c : world.carContacts(dc.id))
      if (c.other == dc.impact_other)
        dc.impact_normal_sum += (c.depth_m + 1e-6) * (car.vehiclePose().orientation * c.normal);
    // Before ODE reports a contact (the body met it within the step, crush_coupling's addApproaching),
    // the normal is the approach's: against the relative velocity.
    Eigen::Vector3d normal = dc.impact_normal_sum;
    if (normal.norm() <= 1e-12) normal = -dc.impact_relative_velocity_mps;
    if (normal.norm() > 1e-12) {
      dc.impact_normal = normal.normalized();
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

  if (points_moved)
    mt.max_deviation_m = std::max(mt.max_deviation_m, deform::maxDeviation(*dc.body_settings, s));
  deform::Penetration pen;
  for (const auto& shape : dc.shapes.exactShapes())
    for (const auto& x : s.positions_m)
      if (deform::penetration(shape, x, pen))
        mt.max_penetration_m = std::max(mt.max_penetration_m, pen.depth_m);

  // Tunnelling: the car's origin (inside its rigid parts) passed into or through a wall or post during
  // this step. The step's own path, not the chord from where the car was at impact: a car that glanced
  // off a short wall's end and slid along its far face crossed that chord, never the wall (random scene
  // 10_13). A car knocked past another, or driven on over a tree it felled, meets neither. Checked before
  // any contact too: a car through a thin wall within one step may never have touched it.
  // The step's obstacle boxes (updateBoxes) keep it to the walls and posts near the path.
  const Eigen::Vector3d& to = car.bodyPose().position_m;
  if (!mt.tunnelled && to != position_before) {
    const Box path{position_before.cwiseMin(to), position_before.cwiseMax(to)};
    for (ObstacleId o = 0; o < obstacle_boxes.size() && !mt.tunnelled; ++o) {
      const ObstacleKind kind = world.obstacleKind(o);
      if ((kind != ObstacleKind::Wall && kind != ObstacleKind::Post) || world.obstacleIsDynamic(o)) continue;
      if (obstacle_boxes[o].overlaps(path))
        mt.tunnelled = segmentMeets(world.obstacleShape(o), position_before, to);
    }
  }

  if (!mt.impacted) return;
  // The rebound is the separation speed: measured while the car touches what it hit and in the step it
  // leaves it, never afterwards (a car steering away from a wall it grazed is not a rebound).
  const bool in_contact = std::find(dc.hit.begin(), dc.hit.end(), dc.impact_other) != dc.hit.end();
  const Eigen::Vector3d relative = car.velocity_mps() - velocityOf(dc.impact_other);
  if (in_contact || dc.in_contact)
    mt.rebound_speed_mps = std::max(mt.rebound_speed_mps, relative.dot(dc.impact_normal));
  dc.in_contact = in_contact;
  mt.restitution = mt.impact_speed_mps > 1e-9 ? mt.rebound_speed_mps / mt.impact_speed_mps : 0.0;
  // Against something fixed, the centre of mass's approach to it along the impact normal (a barrier
  // test's dynamic crush). Against something that moves (another car, a pushed box) that approach also
  // counts how the two turn and slide about each other after the hit: cars pressed into a pile-up
  // "crushed" 3.5-5.7 m with their points never 0.2 m from rest. There it is the body's own crush: the
  // largest motion of a control point back from its rest place along the impact direction. So it is in
  // the visual coupling, whose chassis ODE stops at the surface while the ghost crushes the body.
  const bool fixed = dc.impact_other.kind == EntityRef::Kind::Obstacle &&
                     !world.obstacleIsDynamic(dc.impact_other.index) &&
                     dc.settings.coupling == Coupling::Crush;
  const double separation =
      dc.impact_normal.dot(car.bodyPose().position_m - interiorPoint(worldShapeOf(dc.impact_other)));
  if (fixed) {
    mt.max_dynamic_crush_m = std::max(mt.max_dynamic_crush_m, dc.impact_separation_m - separation);
  } else {
    const auto& rest = dc.body_settings->rest_positions_m;
    for (std::size_t i = 0; i < rest.size(); ++i)
      mt.max_dynamic_crush_m =
          std::max(mt.max_dynamic_crush_m, (rest[i] - s.positions_m[i]).dot(dc.impact_direction_vehicle));
  }
  EnergyTerms& e = mt.energy;
  e.crush_work_J += dc.step_crush_work_J;
  e.other_work_J += dc.step_other_work_J;
  e.plastic_work_J = s.plastic_work_J - dc.plastic_at_impact_J;
  e.kinetic_final_J = carKineticEnergy(dc);
  e.damping_loss_J = dc.damping_loss_J - dc.damping_at_impact_J;
  e.contact_loss_J = dc.contact_loss_J - dc.contact_loss_at_impact_J;
  const deform::BodyEnergy body = deform::bodyEnergy(*dc.body_settings, s);
  e.body_energy_J = body.total_J();
  e.elastic_energy_J = dc.elastic_after_step_J - dc.elastic_at_impact_J;
  e.contact_work_J = dc.contact_work_J - dc.contact_work_at_impact_J;
  e.inertial_work_J = dc.inertial_work_J - dc.inertial_work_at_impact_J;
  e.obstacle_work_J = dc.obstacle_work_J - dc.obstacle_work_at_impact_J;
  e.dissipated_J = e.damping_loss_J + e.contact_loss_J + e.other_work_J;
  e.balance_error_J = e.kinetic_initial_J + e.obstacle_work_J - e.kinetic_final_J - e.plastic_work_J -
                      e.damping_loss_J - e.contact_loss_J - e.elastic_energy_J - e.other_work_J;
}

CrashMetrics Simulation::metrics(CarId car) const {
  const DeformableCar& dc = impl_->of(car);
  CrashMetrics out = dc.metrics;
  if (!out.impacted) return out;
  const auto& rest = dc.body_settings->rest_positions_m;  // the control mesh's points
  const auto& now = dc.body->state().positions_m;
  // The body's own surface: a refined body's is finer than the build's, and encloses the same volume.
  const auto& triangles = dc.body_settings->triangles;
  out.crushed_volume_m3 = dc.build->control_mesh.volume_m3 - deform::enclosedVolume_m3(now, triangles);
  const CrushStations stations = crushStations(triangles, rest, now, dc.impact_direction_vehicle);
  for (std::size_t i = 0; i < rest.size(); ++i)
    out.max_dent_m =
        std::max(out.max_dent_m, -(now[i] - rest[i]).dot(dc.impact_direction_vehicle.normalized()));
  out.crush_profile_m = stations.profile_m;
  out.crush_height_m = stations.height_m;
  out.residual_crush_m = stations.mean_m;
  out.max_residual_crush_m = stations.max_m;
  if (dc.impact_direction_vehicle.norm() > 1e-12)
    out.impact_direction_vehicle = dc.impact_direction_vehicle.normalized();
  return out;
}

}  // namespace vehicle
