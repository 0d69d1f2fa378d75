// A Simulation's state saved and put back bit for bit (simulation.hpp): the world, and per deformable
// car its body, its coupling's memory and its metrics with their accumulators.
#include "simulation_impl.hpp"

#include <deform/body_state.hpp>

#include <cmath>

namespace vehicle {
namespace {

void saveEntity(StateWriter& out, const EntityRef& e) {
  out.flag(e.kind == EntityRef::Kind::Car);
  out.u64(e.index);
}

EntityRef restoreEntity(StateReader& in) {
  EntityRef e;
  e.kind = in.flag() ? EntityRef::Kind::Car : EntityRef::Kind::Obstacle;
  const uint64_t index = in.u64();
  in.expect(index <= UINT32_MAX, "entity index out of range");
  e.index = static_cast<uint32_t>(index);
  return e;
}

/// Every member of CrashMetrics, in one order for both directions (`io` is a writer or a reader).
template <class Io, class Metrics>
void visitMetrics(Io& io, Metrics& m) {
  auto real = [&io](auto& x) {
    if constexpr (std::is_same_v<Io, StateWriter>)
      io.real(x);
    else
      x = io.real();
  };
  auto flag = [&io](auto& x) {
    if constexpr (std::is_same_v<Io, StateWriter>)
      io.flag(x);
    else
      x = io.flag();
  };
  real(m.impact_speed_mps);
  real(m.rebound_speed_mps);
  real(m.restitution);
  real(m.residual_crush_m);
  real(m.max_residual_crush_m);
  real(m.max_dent_m);
  real(m.max_dynamic_crush_m);
  auto& e = m.energy;
  for (auto* x :
       {&e.kinetic_initial_J, &e.plastic_work_J, &e.damping_loss_J, &e.contact_loss_J, &e.elastic_energy_J,
        &e.contact_work_J, &e.inertial_work_J, &e.dissipated_J, &e.kinetic_final_J, &e.crush_work_J,
        &e.other_work_J, &e.body_energy_J, &e.balance_error_J, &e.obstacle_work_J})
    real(*x);
  real(m.max_deviation_m);
  real(m.max_penetration_m);
  flag(m.tunnelled);
  flag(m.diverged);
  real(m.diverged_at_s);
  if constexpr (std::is_same_v<Io, StateWriter>)
    io.text(m.diverged_what);
  else
    m.diverged_what = io.text();
  flag(m.impacted);
}

}  // namespace

void Simulation::Impl::saveCar(StateWriter& out, const DeformableCar& dc) const {
  out.u64(dc.id);
  // The refined topology first (the body's state is read against it): the splits in their order.
  const std::vector<uint32_t> no_splits;
  const std::vector<uint32_t>& splits = dc.hierarchy ? dc.hierarchy->splitOrder() : no_splits;
  out.u64(splits.size());
  for (uint32_t node : splits) out.u64(node);
  // A refined body's masses: they depend on the order its refinements came in.
  out.u64(splits.empty() ? 0 : dc.body_settings->mass_kg.size());
  if (!splits.empty())
    for (double m : dc.body_settings->mass_kg) out.real(m);
  out.u64(dc.refinements);
  out.flag(dc.refine_bounded);
  out.blob(deform::saveState(dc.body->state()));
  out.flag(dc.hull_dirty);
  out.u64(static_cast<uint64_t>(dc.quiet_steps));
  out.vec(dc.previous_velocity_mps);
  out.vec(dc.previous_omega_radps);
  out.vec(dc.ghost_velocity_mps);
  out.vec(dc.ghost_offset_m);
  const CrashMetrics& metrics = dc.metrics;
  visitMetrics(out, metrics);
  out.vec(dc.impact_normal);
  out.vec(dc.impact_direction_vehicle);
  saveEntity(out, dc.impact_other);
  out.real(dc.impact_separation_m);
  out.vec(dc.impact_relative_velocity_mps);
  out.vec(dc.impact_com_m);
  out.vec(dc.impact_other_m);
  out.vec(dc.impact_normal_sum);
  out.u64(static_cast<uint64_t>(dc.impact_steps));
  out.flag(dc.in_contact);
  for (double x :
       {dc.plastic_at_impact_J, dc.plastic_before_step_J, dc.body_energy_at_impact_J, dc.damping_loss_J,
        dc.damping_at_impact_J, dc.contact_work_J, dc.contact_work_at_impact_J, dc.contact_loss_J,
        dc.contact_loss_at_impact_J, dc.contact_loss_before_step_J, dc.elastic_at_impact_J,
        dc.elastic_before_step_J, dc.step_crush_work_J, dc.step_other_work_J, dc.elastic_after_step_J,
        dc.inertial_work_J, dc.inertial_work_at_impact_J, dc.obstacle_work_J, dc.obstacle_work_at_impact_J})
    out.real(x);
  // The energy watch's (it moves nothing: the state hash leaves it out).
  if (!out.forHash()) out.real(dc.link_loss_counted_twice_J);
}

void Simulation::Impl::restoreCar(StateReader& in, DeformableCar& dc) {
  in.expect(in.u64() == dc.id, "deformable car order does not match the scene");
  const uint64_t split_count = in.u64();
  in.expect(split_count <= 4 * dc.settings.max_control_points, "refinement splits out of range");
  std::vector<uint32_t> splits;
  for (uint64_t k = 0; k < split_count; ++k) {
    const uint64_t node = in.u64();
    in.expect(node < UINT32_MAX, "refinement split out of range");
    splits.push_back(static_cast<uint32_t>(node));
  }
  const uint64_t mass_count = in.u64();
  in.expect(mass_count <= 100000, "refined body's point masses out of range");
  std::vector<double> masses;
  for (uint64_t k = 0; k < mass_count; ++k) masses.push_back(in.real());
  dc.refinements = in.u64();
  dc.refine_bounded = in.flag();
  const std::span<const uint8_t> body = in.blob();
  try {
    rebuildRefined(dc, splits, masses);
    dc.body->setState(deform::restoreState(*dc.body_settings, body));
  } catch (const deform::InputError& e) {
    in.fail(std::string("deformable body: ") + e.what());
  }
  dc.hull_dirty = in.flag();
  const uint64_t quiet = in.u64();
  in.expect(quiet <= INT32_MAX, "quiet steps out of range");
  dc.quiet_steps = static_cast<int>(quiet);
  dc.previous_velocity_mps = in.vec();
  dc.previous_omega_radps = in.vec();
  dc.ghost_velocity_mps = in.vec();
  dc.ghost_offset_m = in.vec();
  visitMetrics(in, dc.metrics);
  dc.impact_normal = in.vec();
  dc.impact_direction_vehicle = in.vec();
  dc.impact_other = restoreEntity(in);
  dc.impact_separation_m = in.real();
  dc.impact_relative_velocity_mps = in.vec();
  dc.impact_com_m = in.vec();
  dc.impact_other_m = in.vec();
  dc.impact_normal_sum = in.vec();
  const uint64_t impact_steps = in.u64();
  in.expect(impact_steps <= INT32_MAX, "impact steps out of range");
  dc.impact_steps = static_cast<int>(impact_steps);
  dc.in_contact = in.flag();
  for (double* x :
       {&dc.plastic_at_impact_J, &dc.plastic_before_step_J, &dc.body_energy_at_impact_J, &dc.damping_loss_J,
        &dc.damping_at_impact_J, &dc.contact_work_J, &dc.contact_work_at_impact_J, &dc.contact_loss_J,
        &dc.contact_loss_at_impact_J, &dc.contact_loss_before_step_J, &dc.elastic_at_impact_J,
        &dc.elastic_before_step_J, &dc.step_crush_work_J, &dc.step_other_work_J, &dc.elastic_after_step_J,
        &dc.inertial_work_J, &dc.inertial_work_at_impact_J, &dc.obstacle_work_J,
        &dc.obstacle_work_at_impact_J})
    *x = in.real();
  dc.link_loss_counted_twice_J = in.real();
  // What the last step left for its metrics (contacts, shapes) is not kept: the next step makes its own.
  dc.touching.clear();
  dc.partners.clear();
  dc.partner_in_ode.clear();
  dc.partner_pushed.clear();
  dc.hit.clear();
  dc.shapes.clear();
  dc.world_shape = ObstacleShape{};
}

void Simulation::saveState(StateWriter& out) const {
  impl_->world.saveState(out);
  out.u64(impl_->cars.size());
  for (const auto& dc : impl_->cars) impl_->saveCar(out, *dc);
  // The watch's accumulators resume with the run; they move nothing, so the state hash leaves them out.
  if (out.forHash()) return;
  const EnergyWatch& w = impl_->watch;
  out.flag(w.started);
  for (double x :
       {w.initial_J, w.initial_kinetic_J, w.initial_potential_J, w.lowest_potential_J, w.drive_work_J,
        w.total_mass_kg, w.largest_created_J, w.largest_created_share, w.through_J})
    out.real(x);
  out.u64(w.car_energy_J.size());
  for (std::size_t c = 0; c < w.car_energy_J.size(); ++c) {
    out.real(w.car_energy_J[c]);
    out.flag(c < w.airborne.size() && w.airborne[c] != 0);
    out.real(c < w.apex_m.size() ? w.apex_m[c] : 0.0);
  }
}

void Simulation::restoreState(StateReader& in) {
  impl_->world.restoreState(in);
  in.expect(in.u64() == impl_->cars.size(), "deformable car count does not match the scene");
  for (auto& dc : impl_->cars) impl_->restoreCar(in, *dc);
  EnergyWatch& w = impl_->watch;
  w.started = in.flag();
  for (double* x :
       {&w.initial_J, &w.initial_kinetic_J, &w.initial_potential_J, &w.lowest_potential_J, &w.drive_work_J,
        &w.total_mass_kg, &w.largest_created_J, &w.largest_created_share, &w.through_J})
    *x = in.real();
  const uint64_t count = in.u64();
  in.expect(count == (w.started ? impl_->world.carCount() : 0), "energy watch: car count does not match");
  w.car_energy_J.assign(count, 0.0);
  w.airborne.assign(count, 0);
  w.apex_m.assign(count, 0.0);
  for (std::size_t c = 0; c < count; ++c) {
    w.car_energy_J[c] = in.real();
    w.airborne[c] = in.flag() ? 1 : 0;
    w.apex_m[c] = in.real();
  }
}

}  // namespace vehicle
