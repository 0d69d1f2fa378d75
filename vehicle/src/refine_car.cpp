// Refinement of a car's body at run time (DeformationSettings::refine, deform/refinement.hpp).
#include "simulation_impl.hpp"

#include <deform/error.hpp>

#include <algorithm>
#include <cstdint>
#include <string>

namespace vehicle {
namespace {

// Beyond the step's travel, how near an obstacle must come to a patch to refine it [m]: a substep's
// contact margin and what a step's turn of the car adds at its ends.
constexpr double kRefineMargin_m = 0.05;

/// A body on `settings` with `dc`'s solver parameters, in `state`.
void replaceBody(DeformableCar& dc, std::shared_ptr<const deform::BodySettings> settings,
                 deform::BodyState state) {
  deform::SolverParams params = dc.body->params();
  params.longest_contact_substep_s = contactSubstep_s(dc.settings, settings->pointCount());
  dc.body_settings = std::move(settings);
  dc.body = std::make_unique<deform::DeformableBody>(dc.body_settings, params);
  dc.body->setState(std::move(state));
}

}  // namespace

void Simulation::Impl::refineCar(DeformableCar& dc) const {
  if (!dc.settings.refine || dc.inputs.contacts.empty()) return;
  if (!dc.hierarchy) dc.hierarchy = std::make_unique<deform::SurfaceHierarchy>(dc.build->control_mesh);
  deform::ContactRefinement rule;
  rule.contact_edge_m = dc.settings.contact_edge_m;
  rule.max_points = dc.settings.max_control_points;
  double fastest_mps = 0;
  for (const Eigen::Vector3d& v : dc.inputs.contact_velocity_mps)
    fastest_mps = std::max(fastest_mps, v.norm());
  rule.reach_m = fastest_mps * world.fixedDt_s() + kRefineMargin_m;
  std::vector<Eigen::Vector3d> positions = dc.body->state().positions_m;
  const deform::SurfaceHierarchy::Mark before = dc.hierarchy->mark();
  const deform::RefinementOutcome outcome =
      deform::splitNearContacts(*dc.hierarchy, positions, dc.inputs.contacts, rule);
  dc.refine_bounded = dc.refine_bounded || outcome.bounded;
  if (outcome.splits == 0) return;
  deform::TransferredBody fine =
      deform::transferBody(*dc.hierarchy, before, *dc.body_settings, dc.body->state(), dc.build->description);
  replaceBody(dc, std::move(fine.settings), std::move(fine.state));
  ++dc.refinements;
}

void Simulation::Impl::rebuildRefined(DeformableCar& dc, const std::vector<uint32_t>& splits,
                                      const std::vector<double>& point_mass_kg) const {
  if (splits.empty()) {
    if (!dc.hierarchy) return;
    dc.hierarchy.reset();
    replaceBody(dc, dc.build->body_settings, deform::restState(*dc.build->body_settings));
    return;
  }
  auto hierarchy = std::make_unique<deform::SurfaceHierarchy>(dc.build->control_mesh);
  for (uint32_t node : splits)
    if (node >= hierarchy->nodes().size() || (hierarchy->isLeaf(node) && !hierarchy->split(node, SIZE_MAX)))
      throw deform::InputError("refinement: split " + std::to_string(node) + " is not one of the body's");
  auto settings =
      deform::refinedSettings(*hierarchy, *dc.build->body_settings, dc.build->description, point_mass_kg);
  dc.hierarchy = std::move(hierarchy);
  deform::BodyState rest = deform::restState(*settings);
  replaceBody(dc, std::move(settings), std::move(rest));
}

Simulation::Refinement Simulation::refinement(CarId car) const {
  const DeformableCar& dc = impl_->of(car);
  return {dc.body_settings->pointCount(), dc.refinements, dc.refine_bounded};
}

}  // namespace vehicle
