// DeformableBody's end of a substep: the visual constraint with the rigid stop at the cap, and the
// plastic flow of every constraint with the work it did.
#include <deform/constraints.hpp>
#include <deform/deformable_body.hpp>

#include <algorithm>
#include <cmath>
#include <variant>

#include "body_halves.hpp"
#include "cap_wide.hpp"
#include "columns_wide.hpp"
#include "sweep_wide.hpp"

namespace deform {

void DeformableBody::capDeviation(double h, const StepInputs& inputs, Eigen::Vector3d& core,
                                  const Eigen::Vector3d& core_start, Eigen::Vector3d& tie_push,
                                  StepReport& report) {
  const BodySettings& settings = *settings_;
  auto& x = state_.positions_m;
  const auto& m = settings.mass_kg;
  const std::size_t n = settings.pointCount();
  // A point an obstacle holds cannot give way. At its cap the car's rigid part has reached the obstacle:
  // the core moves to the point instead (a rigid stop of the chassis, whose momentum the obstacle gives),
  // rather than the point being pulled into the obstacle and, through a thin wall, out of its far side.
  // Only force-limited bodies stop this way (an unlimited solve carries the force the stop would).
  held_.clear();
  const bool stops = params_.yield_limited && core_inverse_mass_per_kg_ > 0;
  // A post stops the core across its axis only. A point pressed onto its flat end (a low stub the front
  // rides onto) would otherwise give a normal half up its axis, and the inelastic stop along it turns the
  // car's motion up it as a ramp would: a 0.3 m stub of 3 cm radius threw a car at 250 km/h 14 m up.
  // The body is cut by so thin a thing, not carried over it; its rigid parts meet the post's side.
  const auto stopNormal = [&inputs](uint32_t shape, const Eigen::Vector3d& normal, Eigen::Vector3d& out) {
    out = normal;
    if (shape >= inputs.contacts.size()) return true;
    const ContactShape& contact = inputs.contacts[shape];
    Eigen::Vector3d axis{0, 0, 0};
    if (const auto* cylinder = std::get_if<CylinderShape>(&contact)) axis = cylinder->b_m - cylinder->a_m;
    if (const auto* capsule = std::get_if<CapsuleShape>(&contact)) axis = capsule->b_m - capsule->a_m;
    if (!(axis.squaredNorm() > 0)) return true;
    return acrossAxis(normal, axis.normalized(), out);  // an end's normal: no stop
  };
  if (stops) {
    Eigen::Vector3d normal;
    for (const ContactPoint& c : contacts_)
      if (c.moved_m.squaredNorm() > 0 && stopNormal(c.shape, c.normal, normal))
        held_.push_back({c.point, c.shape, normal});
    for (const FaceContact& c : face_contacts_)
      for (int j = 0; j < (c.corners[2] == c.corners[0] ? 2 : 3); ++j)  // an edge contact: two corners
        if (c.moved_m[j].squaredNorm() > 0 && stopNormal(c.shape, c.normal, normal))
          held_.push_back({c.corners[j], c.shape, normal});
  }
  // Jacobi over the held points, so that no point's index order decides where the stop acts: each pass
  // stops the core at the held points' mean rest place and normal, weighted by how far each is past its
  // cap (a wall met squarely stops the car at the middle of its front, not at whichever point comes
  // first). The stop is an inelastic impulse at that place: it brings the approach of the core's point
  // there (the core's motion, and the turn the stops of this step gave it) to rest along the normal, with
  // the mass the core has at that point, translation and turn together (Mirtich 1996, "Impulse-based
  // dynamic simulation of rigid body systems", the collision impulse with e = 0). So it never does
  // positive work: the kinetic energy falls by half that mass times the approach speed squared. Stopping
  // the core's translation alone and then handing ODE the moment of that impulse turned a car about a
  // post so hard that its front came off it faster than it went in (106 % of the impact energy created
  // at 150 km/h, 0.5 m off the post's centre). What it leaves past the caps (the turn it gives moves no
  // point within the step) is the projection's below; moving the core alone for it, without a velocity
  // (a split impulse), stretched the spokes and columns and created energy in the body's extreme tests.
  constexpr int kMostStopPasses = 4;
  const Eigen::Matrix3d& inverse_inertia = inputs.core_inverse_inertia_per_kg_m2;
  // How far past its cap each held point leaves the core along its normal, summed into the mean rest
  // place and normal, with the largest and its point.
  struct PastCaps {
    double largest_m = 0, total_m = 0;
    const HeldPoint* largest = nullptr;
    Eigen::Vector3d rest_sum{0, 0, 0}, normal_sum{0, 0, 0};
  };
  const auto pastCaps = [&] {
    PastCaps p;
    for (const HeldPoint& held : held_) {
      const uint32_t i = held.point;
      // The obstacle pushes only along its normal: s >= 0 is how far the core is past where the point
      // would be within its cap, |d - s n| <= cap; a point beyond its cap across the normal is the point's
      // own to fix (its projection below).
      const Eigen::Vector3d d = x[i] - (settings.rest_positions_m[i] + core - settings.core_m);
      const double cap = settings.max_deviation_m[i];
      if (d.squaredNorm() <= cap * cap) continue;
      const double along = d.dot(held.normal);
      const double across2 = d.squaredNorm() - along * along;
      if (across2 >= cap * cap) continue;  // beyond the cap across the normal: no push along it helps
      const double s = along - std::sqrt(cap * cap - across2);
      if (!(s > 0)) continue;
      p.total_m += s;
      p.rest_sum += s * settings.rest_positions_m[i];
      p.normal_sum += s * held.normal;
      if (s > p.largest_m) {
        p.largest_m = s;
        p.largest = &held;
      }
    }
    return p;
  };
  for (int pass = 0; pass < kMostStopPasses && !held_.empty(); ++pass) {
    const PastCaps past = pastCaps();
    const HeldPoint* largest = past.largest;
    if (largest == nullptr) break;
    const uint32_t shape = largest->shape;
    const Eigen::Vector3d rest_m = past.rest_sum / past.total_m;
    const Eigen::Vector3d normal = past.normal_sum.norm() > 1e-9 * past.total_m
                                       ? Eigen::Vector3d(past.normal_sum.normalized())
                                       : largest->normal;
    // The core's point at rest_m, relative to the obstacle there.
    const Eigen::Vector3d at_m = rest_m + core - settings.core_m;
    const Eigen::Vector3d lever_m = rest_m - inputs.core_centre_of_mass_m;
    // A movable obstacle's velocity with its moves so far in this substep (this step's pushes and the
    // earlier passes' stops), as the core's is: left out, each pass met the obstacle where it had been and
    // pushed it again (a 628 kg tree hit at 213 km/h left at 49 m/s, the car at 23 m/s: 266 kJ created).
    const double w_obstacle = obstacle_inverse_mass_[shape];
    const Eigen::Vector3d obstacle =
        obstacleVelocity(inputs, shape, at_m) +
        (w_obstacle > 0 ? Eigen::Vector3d(obstacle_shift_m_[shape] / h) : Eigen::Vector3d::Zero());
    const Eigen::Vector3d before_mps = (core - core_start) / h + stop_omega_radps_.cross(lever_m) - obstacle;
    const double approach_mps = -before_mps.dot(normal);
    if (!(approach_mps > 0)) break;  // already coming off it
    // A movable obstacle gives way by its share (inverse masses), as far as what holds it lets it.
    const Eigen::Vector3d arm = lever_m.cross(normal);
    const double inverse_mass = core_inverse_mass_per_kg_ + w_obstacle + arm.dot(inverse_inertia * arm);
    const double j_Ns = approach_mps / inverse_mass;
    const Eigen::Vector3d impulse_Ns = j_Ns * normal;
    if (w_obstacle > 0) obstacle_shift_m_[shape] += heldMove(shape, -(w_obstacle * h) * impulse_Ns);
    stop_omega_radps_ += inverse_inertia * lever_m.cross(impulse_Ns);
    // Its loss: the kinetic energy the inelastic impulse takes, 1/2 j v_n.
    report.contact_loss_J += 0.5 * j_Ns * approach_mps;
    report.contact_impulse_per_obstacle_Ns[shape] += impulse_Ns;
    report.contact_impulse_Ns += impulse_Ns;
    report.core_impulse_Ns += impulse_Ns;
    report.core_angular_impulse_Nms += (rest_m - settings.core_m).cross(impulse_Ns);
    report.contact_moment_Nms += (core_start - settings.core_m + rest_m).cross(impulse_Ns);
    report.obstacle_work_J += impulse_Ns.dot(obstacle);
    core += (core_inverse_mass_per_kg_ * h) * impulse_Ns;
  }
  // The rest are pulled back to the cap. The cap ties a point to the core, so each projection moves both
  // by their inverse masses (PBD, Mueller et al. 2007, eq. 8), point by point: moving only the point and
  // then the core by its reaction diverged once the shell outweighed the core (each pass larger by shell /
  // core mass). The core's move shifts every rest position, so the pass repeats until that is negligible.
  // A point held by an obstacle no longer moves the core once it sits at its cap. A core of 1 % of the
  // body's mass under a wall needs 9-16 passes (sweep_order_test), a car's core one or two.
  constexpr int kMostPasses = 16;
  const double w_core = core_inverse_mass_per_kg_;
  const auto& w = settings.inverse_mass_per_kg;
  const auto deviation = [&](std::size_t i) {
    return Eigen::Vector3d(x[i] - (settings.rest_positions_m[i] + core - settings.core_m));
  };
  const auto project = [&](std::size_t i) {
    const Eigen::Vector3d d = deviation(i);
    const double cap = settings.max_deviation_m[i];
    const double squared = d.squaredNorm();
    if (squared <= cap * cap || !(w[i] + w_core > 0)) return;
    const double length = std::sqrt(squared);
    const Eigen::Vector3d correction = ((length - cap) / ((w[i] + w_core) * length)) * d;
    x[i] -= w[i] * correction;
    core += w_core * correction;
    tie_push -= m[i] * w[i] * correction;  // the point's momentum change; the core's is opposite
  };
  // Most points are far inside their caps. The halves (SolverParams::threads) first list the points
  // within kNear_m of theirs, with the core where it stands; the pass projects only those, in point
  // order, while the core has moved less than kNear_m, so every point left out is surely inside its cap
  // (by the triangle inequality, with 1e-9 m to spare for rounding) and projecting it would do nothing:
  // the result is the one-by-one pass's, bit for bit. Past that move, the pass checks every point.
  // Each thread reading only its own half keeps the positions in its own cache for the next substep.
  // Without SolverParams::wide_sweep, every point is checked one by one (the reference).
  constexpr double kNear_m = 1e-3, kRounding_m = 1e-9;
  for (int pass = 0; pass < kMostPasses; ++pass) {
    const Eigen::Vector3d core_before = core;
    const auto moved_far = [&] { return (core - core_before).norm() >= kNear_m - kRounding_m; };
    std::size_t next = 0;  // from here on every point is checked
    if (params_.wide_sweep) {
      forEachHalf(params_.threads, [&](int half) {
        std::vector<uint32_t>& near = near_cap_of_half_[half];
        near.clear();
        const auto [begin, end] = halfOf(n, half);
        // (A point whose deviation is not a number is listed, as the pass would take it.)
        listNearCaps(x.data(), settings.rest_positions_m.data(), settings.max_deviation_m.data(), core,
                     settings.core_m, kNear_m, begin, end, true, near);
      });
      for (const auto& near : near_cap_of_half_)
        for (const uint32_t i : near) {
          if (moved_far()) break;
          project(i);
          next = i + 1;
        }
      if (!moved_far()) next = n;  // every point not listed is surely inside its cap
    }
    for (std::size_t i = next; i < n; ++i) project(i);
    if ((core - core_before).squaredNorm() <= 1e-24) break;  // under 1e-12 m
  }
}

void DeformableBody::plasticity(StepReport& report, const Eigen::Vector3d& core_m, double h) {
  const BodySettings& settings = *settings_;
  const auto& x = state_.positions_m;
  const auto& laws = settings.plastic_laws;
  // One constraint: new rest length by the return map; the plastic work is the force the constraint
  // carried along the flow times the flow |dL| (the 1D sigma_y d eps_p, a dissipation sigma eps_p' >= 0:
  // Simo & Hughes 1998, "Computational Inelasticity", section 1.2). That force is what the solver applied
  // this substep, lambda / h^2 (XPBD eq. 18: a stiff constraint the iterations did not converge carries
  // less than its elastic formula says), taken along the flow and never below zero, and never more than
  // the yield force left after the flow, |l - L'| / alpha. An unconverged solve can leave a constraint
  // past its band opposite to the force it applied (a bar pushed apart that then flows longer): its rest
  // length still follows the geometry, but no force of it did that work (with |lambda| such flow booked
  // 4.5 kJ the side pole's shell never took at 2000 points; docs/CRASH_CALIBRATION.md, "Energy account").
  const double inv_h2 = 1.0 / (h * h);
  // Most constraints stay inside their cached elastic band (elasticBand): a squared length and two
  // comparisons; the square root and the return map only for the rest, with the same result as always.
  auto flow = [&](double length_m2, ElasticBand& band, double& rest, double original,
                  const YieldLimits& yield, uint32_t material, double compliance, double lambda,
                  YieldForce& carries, double& work_J) {
    if (band.holds(length_m2)) return;
    const double length = std::sqrt(length_m2);
    const double moved = plasticRestLength(length, rest, original, yield, laws[material]);
    if (moved == rest) return;
    if (params_.yield_limited) carries = yieldForce(compliance, moved, original, yield, laws[material]);
    // A rigid constraint (alpha = 0) has no defined yield force: its flow is counted at zero work.
    if (compliance > 0) {
      // lambda < 0 pulls the ends together (tension), lambda > 0 pushes them apart.
      const double along_flow_N = std::max(0.0, moved > rest ? -lambda : lambda) * inv_h2;
      const double force_N = std::min(along_flow_N, std::abs(length - moved) / compliance);
      work_J += force_N * std::abs(moved - rest);
    }
    rest = moved;
    band = elasticBand(moved, original, yield, laws[material]);
  };
  const Eigen::Vector3d shift = core_m - settings.core_m;
  // Each constraint flows on its own: the halves of each kind side by side (SolverParams::threads),
  // each with its own sum of the work.
  double work_of_half[2] = {0, 0};
  forEachHalf(params_.threads, [&](int half) {
    double work_J = 0;  // a local, stored once: the two halves' sums share a cache line
    const auto [edges_begin, edges_end] = halfOf(settings.edges.size(), half);
    // Those outside their band, found four at a time where the machine can (outsideBands), flow in order.
    std::vector<uint32_t>& outside = outside_[half];
    std::vector<double>& outside_m2 = outside_m2_[half];
    outside.clear();
    outside_m2.clear();
    outsideBands(x.data(), edge_pairs_.data(), edge_band_.data(), edges_begin, edges_end, params_.wide_sweep,
                 outside, outside_m2);
    for (std::size_t j = 0; j < outside.size(); ++j) {
      const std::size_t k = outside[j];
      const EdgeConstraint& c = settings.edges[k];
      flow(outside_m2[j], edge_band_[k], state_.edge_rest_m[k], settings.edge_rest_m[k],
           settings.edge_yield[k], c.material, c.compliance_m_per_N, edge_lambda_[k], edge_yield_N_[k],
           work_J);
    }
    const auto [spokes_begin, spokes_end] = halfOf(settings.spokes.size(), half);
    if (settings.anchored_columns) {
      // Nearly every column is elastic: skip those without a square root (columnSurelyElastic), found four
      // at a time where the machine can.
      outside.clear();
      columnsNotSurelyElastic(x.data(), settings.spokes.data(), state_.column_rest_m.data(),
                              settings.spoke_normal.data(), settings.spoke_yield.data(), shift, spokes_begin,
                              spokes_end, params_.wide_sweep, outside);
      for (const uint32_t k : outside) {
        const SpokeConstraint& c = settings.spokes[k];
        Eigen::Vector3d& rest = state_.column_rest_m[k];
        const Eigen::Vector3d local = x[c.point] - shift;
        const Eigen::Vector3d moved =
            plasticColumnRest(local, rest, settings.rest_positions_m[c.point], settings.spoke_normal[k],
                              settings.spoke_rest_m[k], settings.spoke_yield[k], laws[c.material]);
        if (moved == rest) continue;
        if (c.compliance_m_per_N > 0) {
          // The column pushes its point along lambda, and the rest place flows along the displacement,
          // against it: the force along the flow is -lambda . (flow direction).
          const Eigen::Vector3d flow_m = moved - rest;
          const double flow_length_m = flow_m.norm();
          const double along_flow_N =
              flow_length_m > 0 ? std::max(0.0, -column_lambda_[k].dot(flow_m) / flow_length_m) * inv_h2
                                : 0.0;
          const double force_N = std::min(along_flow_N, (local - moved).norm() / c.compliance_m_per_N);
          work_J += force_N * flow_length_m;
        }
        rest = moved;
        refreshColumn(k);
      }
    } else {
      for (std::size_t k = spokes_begin; k < spokes_end; ++k) {
        const SpokeConstraint& c = settings.spokes[k];
        flow((x[c.point] - core_m - settings.spoke_anchor_m[k]).squaredNorm(), spoke_band_[k],
             state_.spoke_rest_m[k], settings.spoke_rest_m[k], settings.spoke_yield[k], c.material,
             c.compliance_m_per_N, spoke_lambda_[k], spoke_yield_N_[k], work_J);
      }
    }
    const auto [bends_begin, bends_end] = halfOf(settings.bends.size(), half);
    outside.clear();
    outside_m2.clear();
    outsideBands(x.data(), bend_pairs_.data(), bend_band_.data(), bends_begin, bends_end, params_.wide_sweep,
                 outside, outside_m2);
    for (std::size_t j = 0; j < outside.size(); ++j) {
      const std::size_t k = outside[j];
      const BendConstraint& c = settings.bends[k];
      flow(outside_m2[j], bend_band_[k], state_.bend_rest_m[k], settings.bend_rest_m[k],
           settings.bend_yield[k], c.material, c.compliance_m_per_N, bend_lambda_[k], bend_yield_N_[k],
           work_J);
    }
    work_of_half[half] = work_J;
  });
  const double work_J = work_of_half[0] + work_of_half[1];
  state_.plastic_work_J += work_J;
  report.plastic_work_J += work_J;
}

}  // namespace deform
