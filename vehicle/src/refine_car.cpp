// Refinement of a car's body at run time (DeformationSettings::refine, deform/refinement.hpp).
#include "simulation_impl.hpp"

#include <deform/error.hpp>

#include <algorithm>
#include <cmath>
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

/// Another car's control points in this car's frame, as a convex support shape (its hull): what a partner
/// asks of this car's surface (bodies stepped as one meet through deform's links, not as shapes).
struct PointCloud {
  std::vector<Eigen::Vector3d> points_m;
  static Eigen::Vector3d support(const void* user, const Eigen::Vector3d& direction) {
    const auto& points = static_cast<const PointCloud*>(user)->points_m;
    std::size_t best = 0;
    double reach = -HUGE_VAL;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double along = points[i].dot(direction);
      if (along > reach) {
        reach = along;
        best = i;
      }
    }
    return points[best];
  }
};

}  // namespace

void Simulation::Impl::refineCar(DeformableCar& dc) const {
  if (!dc.settings.refine || (dc.inputs.contacts.empty() && dc.partners.empty())) return;
  if (!dc.hierarchy) dc.hierarchy = std::make_unique<deform::SurfaceHierarchy>(dc.build->control_mesh);
  deform::ContactRefinement rule;
  rule.contact_edge_m = dc.settings.contact_edge_m;
  rule.max_points = dc.settings.max_control_points;
  double fastest_mps = 0;
  for (const Eigen::Vector3d& v : dc.inputs.contact_velocity_mps)
    fastest_mps = std::max(fastest_mps, v.norm());
  rule.reach_m = fastest_mps * world.fixedDt_s() + kRefineMargin_m;
  // The partners' surfaces, each where it is now, within the reach of their closing speed.
  std::vector<deform::ContactShape> shapes = dc.inputs.contacts;
  std::vector<PointCloud> clouds(dc.partners.size());
  const Eigen::Quaterniond to_vehicle = dc.frame.orientation.conjugate();
  const Eigen::Vector3d own_mps = world.car(dc.id).velocity_mps();
  for (std::size_t k = 0; k < dc.partners.size(); ++k) {
    const DeformableCar& other = of(dc.partners[k]);
    PointCloud& cloud = clouds[k];
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : other.world_shape.vertices_m) {
      cloud.points_m.push_back(to_vehicle * (p - dc.frame.position_m));
      centre += cloud.points_m.back();
    }
    if (cloud.points_m.empty()) continue;
    centre /= static_cast<double>(cloud.points_m.size());  // inside the hull: the mean of its points
    // Only its hull's corners can be a support point: the search runs over those (a refined partner has
    // thousands of points, and the search ran per query of every leaf near it).
    try {
      cloud.points_m = deform::convexHull(cloud.points_m, "partner", deform::FacetSplit::Diagonals).points_m;
    } catch (const deform::InputError&) {  // a flat or degenerate cloud: every point, as it is
    }
    deform::ConvexSupportShape hull;
    hull.support = &PointCloud::support;
    hull.user = &cloud;
    hull.centre_m = centre;
    for (const Eigen::Vector3d& p : cloud.points_m)
      hull.bounding_radius_m = std::max(hull.bounding_radius_m, (p - hull.centre_m).norm());
    deform::boundingBox(hull);
    shapes.push_back(hull);
    fastest_mps = std::max(fastest_mps, (world.car(dc.partners[k]).velocity_mps() - own_mps).norm());
  }
  rule.reach_m = fastest_mps * world.fixedDt_s() + kRefineMargin_m;
  std::vector<Eigen::Vector3d> positions = dc.body->state().positions_m;
  const deform::SurfaceHierarchy::Mark before = dc.hierarchy->mark();
  const deform::RefinementOutcome outcome = deform::splitNearContacts(*dc.hierarchy, positions, shapes, rule);
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
