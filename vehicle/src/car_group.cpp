// Cars whose deformable bodies meet, stepped as one (simulation_impl.hpp): the groups, and each group's
// links (where one car's vehicle frame lies in another's and how it moves) for deform::stepGroup.
#include "simulation_impl.hpp"

#include <deform/body_group.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace vehicle {

std::vector<std::vector<std::size_t>> Simulation::Impl::bodyGroups() const {
  // Union-find over the partners (a pair joins whichever car found the other within reach).
  const std::size_t n = cars.size();
  std::vector<std::size_t> root(n);
  std::iota(root.begin(), root.end(), std::size_t{0});
  auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  auto join = [&](std::size_t i, std::size_t j) {
    const std::size_t ri = find(i), rj = find(j);
    if (ri != rj) root[std::max(ri, rj)] = std::min(ri, rj);  // the root is the group's first car
  };
  for (std::size_t i = 0; i < n; ++i)
    for (const CarId other : cars[i]->partners) join(i, static_cast<std::size_t>(index_of[other]));
  // Cars that push the same free obstacle (a box between them): deform shares it within the substeps
  // (StepInputs::contact_keys), so they are stepped as one too. The first car touching each obstacle.
  std::vector<std::pair<uint64_t, std::size_t>> first_pusher;
  for (std::size_t i = 0; i < n; ++i) {
    const deform::StepInputs& in = cars[i]->inputs;
    for (std::size_t k = 0; k < in.contact_keys.size(); ++k) {
      if (in.contact_keys[k] == 0) continue;
      const auto known = std::find_if(first_pusher.begin(), first_pusher.end(),
                                      [&](const auto& f) { return f.first == in.contact_keys[k]; });
      if (known == first_pusher.end())
        first_pusher.push_back({in.contact_keys[k], i});
      else
        join(known->second, i);
    }
  }
  std::vector<std::vector<std::size_t>> groups;
  std::vector<std::size_t> group_of(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = find(i);
    if (r == i) {
      group_of[i] = groups.size();
      groups.push_back({i});
    } else {
      groups[group_of[r]].push_back(i);
    }
  }
  return groups;
}

void Simulation::Impl::solveGroup(const std::vector<std::size_t>& group) {
  std::vector<deform::DeformableBody*> bodies;
  std::vector<const deform::StepInputs*> inputs;
  for (const std::size_t i : group) {
    bodies.push_back(cars[i]->body.get());
    inputs.push_back(&cars[i]->inputs);
  }
  auto slot = [&](CarId id) {
    return static_cast<uint32_t>(
        std::find(group.begin(), group.end(), static_cast<std::size_t>(index_of[id])) - group.begin());
  };
  // One link per pair of partners, a the car first in order; the frames as ODE's step left them (the same
  // as each car's prepareCar took for its obstacles).
  std::vector<deform::BodyLink> links;
  for (const std::size_t i : group)
    for (const CarId other : cars[i]->partners) {
      const uint32_t a = slot(cars[i]->id), b = slot(other);
      const uint32_t first = std::min(a, b), second = std::max(a, b);
      const bool known = std::any_of(links.begin(), links.end(), [&](const deform::BodyLink& l) {
        return l.a == first && l.b == second;
      });
      if (known) continue;
      const DeformableCar& ca = *cars[group[first]];
      const DeformableCar& cb = *cars[group[second]];
      const Eigen::Matrix3d ra = ca.frame.orientation.toRotationMatrix();
      const Eigen::Matrix3d rb = cb.frame.orientation.toRotationMatrix();
      const Eigen::Vector3d core_world_m = ca.frame.toWorld(ca.body_settings->core_m);
      const EntityRef self{EntityRef::Kind::Car, ca.id}, partner{EntityRef::Kind::Car, cb.id};
      deform::BodyLink link;
      link.a = first;
      link.b = second;
      link.rotation_b_to_a = ra.transpose() * rb;
      link.translation_b_to_a_m = ra.transpose() * (cb.frame.position_m - ca.frame.position_m);
      link.velocity_mps =
          ra.transpose() * (velocityOf(partner, core_world_m) - velocityOf(self, core_world_m));
      link.angular_velocity_radps = ra.transpose() * (angularVelocityOf(partner) - angularVelocityOf(self));
      // Visual: the two bodies meet where their ghosts are (DeformableCar::ghost_velocity_mps; zero in the
      // crush coupling).
      if (ca.settings.coupling == Coupling::Visual) {
        link.translation_b_to_a_m += link.rotation_b_to_a * cb.ghost_offset_m - ca.ghost_offset_m;
        link.velocity_mps += link.rotation_b_to_a * cb.ghost_velocity_mps - ca.ghost_velocity_mps;
      }
      link.friction = std::sqrt(ca.settings.contact_friction * cb.settings.contact_friction);
      links.push_back(link);
    }
  std::vector<deform::LinkReport> link_reports;
  const std::vector<deform::StepReport> reports =
      deform::stepGroup(bodies, inputs, links, world.fixedDt_s(), &link_reports);
  for (std::size_t k = 0; k < group.size(); ++k) {
    DeformableCar& dc = *cars[group[k]];
    dc.report = reports[k];
    dc.elastic_after_step_J = dc.body->carriedElasticEnergy_J();
    ++dc.deform_steps;
    dc.partner_pushed.assign(dc.partners.size(), 0);
  }
  // Which partners' bodies pushed each other this step (the metrics' impact window). Each body's report
  // books a link's loss as its own (against the other as its obstacle): the energy watch counts it once.
  for (std::size_t l = 0; l < links.size(); ++l) {
    cars[group[links[l].a]]->link_loss_counted_twice_J += link_reports[l].loss_J;
    if (link_reports[l].impulse_on_a_Ns.squaredNorm() == 0) continue;
    DeformableCar& ca = *cars[group[links[l].a]];
    DeformableCar& cb = *cars[group[links[l].b]];
    for (std::size_t k = 0; k < ca.partners.size(); ++k)
      if (ca.partners[k] == cb.id) ca.partner_pushed[k] = 1;
    for (std::size_t k = 0; k < cb.partners.size(); ++k)
      if (cb.partners[k] == ca.id) cb.partner_pushed[k] = 1;
  }
}

}  // namespace vehicle
