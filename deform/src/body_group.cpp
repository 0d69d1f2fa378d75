// Bodies stepped as one (body_group.hpp): interleaved substeps, and point-triangle contacts between
// their surfaces projected in the same sweeps, both sides moving by their inverse masses.
#include <deform/error.hpp>

#include "body_group_impl.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace deform {

namespace {

// Jacobi passes over the links' contacts per sweep: each under-relaxed (project), one pass left points
// inside that the next substep threw out. Two identical bodies head-on (body_group_test.cpp), energy the
// contacts created, 60 / 250 points: 1 pass 2.2 / 4.8 kJ, 2 passes 1.8 / 1.0, 4 passes 0.40 / 0.43,
// 8 passes 0.14 / 0.06 (of 96 kJ).
constexpr int kContactPasses = 4;

void checkLink(const BodyLink& link, std::size_t count, std::size_t k) {
  const std::string field = "links[" + std::to_string(k) + "]";
  if (link.a >= count || link.b >= count || link.a == link.b)
    throw InputError(field + ": a and b must be two different bodies of the group");
  const Eigen::Matrix3d& r = link.rotation_b_to_a;
  if (!r.allFinite() || !((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9) ||
      !(r.determinant() > 0))
    throw InputError(field + ".rotation_b_to_a: not a rotation");
  if (!link.translation_b_to_a_m.allFinite()) throw InputError(field + ".translation_b_to_a_m: not finite");
  if (!link.velocity_mps.allFinite()) throw InputError(field + ".velocity_mps: not finite");
  if (!link.angular_velocity_radps.allFinite())
    throw InputError(field + ".angular_velocity_radps: not finite");
  if (!std::isfinite(link.friction) || link.friction < 0)
    throw InputError(field + ".friction: must be finite and >= 0");
}

}  // namespace

std::vector<StepReport> BodyGroup::step(const std::vector<const StepInputs*>& inputs,
                                        std::vector<LinkReport>* link_reports) {
  const std::size_t count = bodies_.size();
  if (inputs.size() != count) throw InputError("stepGroup: one inputs entry per body");
  for (std::size_t i = 0; i < count; ++i)
    if (bodies_[i] == nullptr || inputs[i] == nullptr)
      throw InputError("stepGroup: a body or its inputs missing");
  for (std::size_t k = 0; k < links_.size(); ++k) checkLink(links_[k], count, k);
  uint32_t substeps = 1, iterations = 1;
  double longest_s = HUGE_VAL;
  for (DeformableBody* b : bodies_) {
    substeps = std::max(substeps, b->params_.substeps);
    iterations = std::max(iterations, b->params_.iterations);
    longest_s = std::min(longest_s, b->params_.longest_contact_substep_s);
  }
  substeps = substepsNoLongerThan(dt_s_, substeps, longest_s);  // the bodies are in contact
  for (std::size_t i = 0; i < count; ++i) body(static_cast<uint32_t>(i)).beginStep(*inputs[i], dt_s_, true);
  findShared(inputs);
  h_s_ = dt_s_ / static_cast<double>(substeps);
  for (DeformableBody* b : bodies_) {
    b->substeps_ = substeps;
    b->h_s_ = h_s_;
  }
  state_.assign(links_.size(), LinkState{});
  for (uint32_t k = 1; k <= substeps; ++k) {
    for (DeformableBody* b : bodies_) b->beginSubstep(k);
    for (std::size_t l = 0; l < links_.size(); ++l) {
      state_[l].start_behind_s = static_cast<double>(substeps - k + 1) * h_s_;
      state_[l].behind_s = static_cast<double>(substeps - k) * h_s_;
      findContacts(l);
    }
    // A shared obstacle: every body pushes it from where the last pass left it, and it moves by the sum
    // of their pushes (Jacobi, as the contacts between the bodies). One body after the other made the
    // split depend on the order the cars are listed in: two sedans pinching a box head-on, 21.4 / 20.5 kJ
    // of plastic work, and 0.5-0.7 kJ moved between them with the order swapped; so, the same either way.
    for (uint32_t it = 0; it < iterations; ++it) {
      for (uint32_t i = 0; i < count; ++i)
        if (it < bodies_[i]->params_.iterations) {
          takeShift(i);
          bodies_[i]->iterate();
          addShift(i);
        }
      sumShifts();
      for (int pass = 0; pass < kContactPasses; ++pass) project();
    }
    for (uint32_t i = 0; i < count; ++i) {
      takeShift(i);
      bodies_[i]->settleSubstep();
      addShift(i);
    }
    sumShifts();
    for (std::size_t l = 0; l < links_.size(); ++l) account(l);
    for (uint32_t i = 0; i < count; ++i) takeShift(i);
    for (DeformableBody* b : bodies_) b->endSubstep();
    alignShared();
    for (SharedObstacle& o : shared_) o.shift_m.setZero();
  }
  std::vector<StepReport> reports;
  for (DeformableBody* b : bodies_) reports.push_back(b->endStep());
  // A shared obstacle's displacement and velocity change are reported once, by its first holder: the
  // caller hands each report's to the obstacle.
  for (const SharedObstacle& o : shared_)
    for (std::size_t h = 1; h < o.holders.size(); ++h) {
      const auto [i, k] = o.holders[h];
      reports[i].obstacle_displacement_m[k].setZero();
      reports[i].obstacle_velocity_change_mps[k].setZero();
    }
  if (link_reports) {
    link_reports->clear();
    for (const LinkState& s : state_) link_reports->push_back(s.report);
  }
  return reports;
}

void BodyGroup::findShared(const std::vector<const StepInputs*>& inputs) {
  shared_.clear();
  to_world_.clear();
  std::vector<std::pair<uint64_t, std::pair<uint32_t, uint32_t>>> keyed;  // (key, (body, contact))
  for (uint32_t i = 0; i < bodies_.size(); ++i) {
    const StepInputs& in = *inputs[i];
    to_world_.push_back(in.frame_to_world);
    for (uint32_t k = 0; k < in.contact_keys.size() && k < in.contacts.size(); ++k)
      if (in.contact_keys[k] != 0 && k < in.contact_inverse_mass_per_kg.size() &&
          in.contact_inverse_mass_per_kg[k] > 0)
        keyed.push_back({in.contact_keys[k], {i, k}});
  }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  for (std::size_t j = 0; j < keyed.size();) {
    std::size_t end = j + 1;
    while (end < keyed.size() && keyed[end].first == keyed[j].first) ++end;
    if (end - j > 1) {
      SharedObstacle o;
      for (std::size_t h = j; h < end; ++h) o.holders.push_back(keyed[h].second);
      shared_.push_back(std::move(o));
    }
    j = end;
  }
}

void BodyGroup::takeShift(uint32_t i) {
  for (const SharedObstacle& o : shared_)
    for (const auto& [b, k] : o.holders)
      if (b == i) bodies_[i]->obstacle_shift_m_[k] = to_world_[i].transpose() * o.shift_m;
}

void BodyGroup::addShift(uint32_t i) {
  for (SharedObstacle& o : shared_)
    for (const auto& [b, k] : o.holders)
      if (b == i) o.pushes_m += to_world_[i] * bodies_[i]->obstacle_shift_m_[k] - o.shift_m;
}

void BodyGroup::sumShifts() {
  for (SharedObstacle& o : shared_) {
    // Each push was held back by what holds the obstacle; their sum is too (the first holder's normals,
    // every holder's in its own frame).
    const auto [first, k] = o.holders.front();
    DeformableBody& f = *bodies_[first];
    f.obstacle_shift_m_[k] = to_world_[first].transpose() * o.shift_m;
    o.shift_m += to_world_[first] * f.heldMove(k, to_world_[first].transpose() * o.pushes_m);
    o.pushes_m.setZero();
  }
}

void BodyGroup::alignShared() {
  for (const SharedObstacle& o : shared_) {
    const auto [first, first_k] = o.holders.front();
    const Eigen::Vector3d offset_m = to_world_[first] * bodies_[first]->obstacle_offset_m_[first_k];
    const Eigen::Vector3d dv_mps = to_world_[first] * bodies_[first]->obstacle_dv_mps_[first_k];
    for (std::size_t h = 1; h < o.holders.size(); ++h) {
      const auto [b, k] = o.holders[h];
      bodies_[b]->obstacle_offset_m_[k] = to_world_[b].transpose() * offset_m;
      bodies_[b]->obstacle_dv_mps_[k] = to_world_[b].transpose() * dv_mps;
    }
  }
}

void BodyGroup::project() {
  // C = n . (P - Q) >= 0, P = sum p_k x_k the place on the point side, Q = sum q_k y_k its nearest place on
  // the other, n fixed for the substep; both sides move by their inverse masses (PBD, Mueller et al. 2007,
  // eq. 8: grad_xk C = p_k n, grad_yk C = -q_k n). Friction takes out the relative tangential travel over
  // the substep, at most `friction` times the depth this correction removed (as projectContact).
  // Jacobi over every link's contacts: every correction is found from the same positions, then applied,
  // each scaled by one over the most contacts any of its corners is in (so that a corner shared by
  // several is not moved several times over; a uniform scale keeps each contact's momentum balanced). In
  // a Gauss-Seidel pass the contact solved last wins, and with force-limited columns in series (two
  // fronts, equal yield) that order decided which car crushed: 49 / 35 kJ head-on, reversed 37 / 46 kJ.
  // Mass splitting (Tonge et al. 2012: a point in k contacts as k copies of a k-th of its mass, the copies
  // averaged) resolves more per pass but overshot in a pile of cars: the traffic runner left -12.6 % of
  // its energy unexplained (-146 % at 250 points) against -4.9 % with this scaling.
  counts_.resize(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    counts_[i].assign(bodies_[i]->state_.positions_m.size(), 0.0);
  corrections_.resize(links_.size());
  for (std::size_t l = 0; l < links_.size(); ++l) {  // every correction from the same positions
    const BodyLink& link = links_[l];
    const LinkState& ls = state_[l];
    const DeformableBody& a = body(link.a);
    const DeformableBody& b = body(link.b);
    corrections_[l].assign(ls.contacts.size(), Eigen::Vector3d::Zero());
    const double depenetration_m =
        std::min(a.params_.max_depenetration_mps, b.params_.max_depenetration_mps) * h_s_;
    for (std::size_t n = 0; n < ls.contacts.size(); ++n) {
      const Contact& c = ls.contacts[n];
      const bool point_in_b = c.point_side == 1;
      const DeformableBody& pb = point_in_b ? b : a;
      const DeformableBody& tb = point_in_b ? a : b;
      const Eigen::Vector3d p =
          placeOf(link, point_in_b, pb.state_.positions_m, c.points, c.point_bary, ls.behind_s);
      const Eigen::Vector3d q =
          placeOf(link, !point_in_b, tb.state_.positions_m, c.corners, c.bary, ls.behind_s);
      const Eigen::Vector3d p_start =
          placeOf(link, point_in_b, pb.previous_m_, c.points, c.point_bary, ls.start_behind_s);
      const Eigen::Vector3d q_start =
          placeOf(link, !point_in_b, tb.previous_m_, c.corners, c.bary, ls.start_behind_s);
      // A place that began the substep inside the other surface comes out of that depth no faster than
      // the bodies' max_depenetration_mps, as against an obstacle; motion further in is stopped in full.
      const double start_gap_m = c.normal.dot(p_start - q_start);
      const double allowed_m = start_gap_m < 0 ? std::min(0.0, start_gap_m + depenetration_m) : 0.0;
      const double violation = c.normal.dot(p - q) - allowed_m;
      if (violation >= 0) continue;
      const double denominator = denominatorOf(c, pb, tb);
      if (!(denominator > 0)) continue;
      Eigen::Vector3d correction = (-violation / denominator) * c.normal;  // per unit inverse mass
      if (link.friction > 0) {
        // The relative travel over the substep once the normal correction is made.
        const Eigen::Vector3d travel = (p - p_start) - (q - q_start) + denominator * correction;
        const Eigen::Vector3d tangential = travel - c.normal.dot(travel) * c.normal;
        const double length = tangential.norm(), limit = -link.friction * violation;
        const Eigen::Vector3d removed =
            length <= limit ? tangential : Eigen::Vector3d(tangential * (limit / length));
        correction -= removed / denominator;
      }
      corrections_[l][n] = correction;
      std::vector<double>& point_count = counts_[point_in_b ? link.b : link.a];
      std::vector<double>& corner_count = counts_[point_in_b ? link.a : link.b];
      for (int j = 0; j < 3; ++j) {
        if (c.point_bary[j] != 0) ++point_count[c.points[j]];
        if (c.bary[j] != 0) ++corner_count[c.corners[j]];
      }
    }
  }
  for (std::size_t l = 0; l < links_.size(); ++l) {  // applied, each scaled by the most contacts at a corner
    const BodyLink& link = links_[l];
    LinkState& ls = state_[l];
    DeformableBody& a = body(link.a);
    DeformableBody& b = body(link.b);
    const Eigen::Matrix3d& r = link.rotation_b_to_a;
    for (std::size_t n = 0; n < ls.contacts.size(); ++n) {
      if (corrections_[l][n].squaredNorm() == 0) continue;
      Contact& c = ls.contacts[n];
      const bool point_in_b = c.point_side == 1;
      DeformableBody& pb = point_in_b ? b : a;
      DeformableBody& tb = point_in_b ? a : b;
      const std::vector<double>& point_count = counts_[point_in_b ? link.b : link.a];
      const std::vector<double>& corner_count = counts_[point_in_b ? link.a : link.b];
      double most = 1;
      for (int j = 0; j < 3; ++j) {
        if (c.point_bary[j] != 0) most = std::max(most, point_count[c.points[j]]);
        if (c.bary[j] != 0) most = std::max(most, corner_count[c.corners[j]]);
      }
      const Eigen::Vector3d correction = corrections_[l][n] / most;
      const Eigen::Vector3d to_b = r.transpose() * correction;
      for (int j = 0; j < 3; ++j) {
        if (c.point_bary[j] != 0)
          pb.state_.positions_m[c.points[j]] +=
              (pb.settings_->inverse_mass_per_kg[c.points[j]] * c.point_bary[j]) *
              (point_in_b ? to_b : correction);
        if (c.bary[j] != 0)
          tb.state_.positions_m[c.corners[j]] -=
              (tb.settings_->inverse_mass_per_kg[c.corners[j]] * c.bary[j]) *
              (point_in_b ? correction : to_b);
      }
      c.push_x_h += correction;  // sum m_k dx_k over the point side's corners
    }
  }
}

double BodyGroup::denominatorOf(const Contact& c, const DeformableBody& pb, const DeformableBody& tb) {
  double denominator = 0;
  for (int j = 0; j < 3; ++j) {
    if (c.point_bary[j] != 0)
      denominator += pb.settings_->inverse_mass_per_kg[c.points[j]] * c.point_bary[j] * c.point_bary[j];
    if (c.bary[j] != 0)
      denominator += tb.settings_->inverse_mass_per_kg[c.corners[j]] * c.bary[j] * c.bary[j];
  }
  return denominator;
}

void BodyGroup::account(std::size_t l) {
  // Each contact's impulse J on the point side (a's frame), spread over its corners by their weights, and
  // -J on the other side's. Each body books the other's surface as its obstacle: the obstacle's work
  // J . V (V the other side's mean velocity over the substep relative to this body's frame) and the loss
  // -J . (u - V) (u its own side's), as DeformableBody::contactLoss does against an obstacle. The two
  // losses are the same energy, taken from the relative motion of the two bodies.
  const BodyLink& link = links_[l];
  LinkState& ls = state_[l];
  DeformableBody& a = body(link.a);
  DeformableBody& b = body(link.b);
  const Eigen::Matrix3d& r = link.rotation_b_to_a;
  const double inv_h = 1.0 / h_s_;
  // A place's mean velocity over the substep relative to its own body's frame, (v0 + v1) / 2.
  auto mean = [&](const DeformableBody& one, const std::array<uint32_t, 3>& k, const Eigen::Vector3d& w) {
    Eigen::Vector3d u{0, 0, 0};
    for (int j = 0; j < 3; ++j)
      if (w[j] != 0)
        u += w[j] * 0.5 *
             (one.state_.velocities_mps[k[j]] +
              (one.state_.positions_m[k[j]] - one.previous_m_[k[j]]) * inv_h);
    return u;
  };
  // Books impulse `j` (this body's frame) on the place `k`, `w` of `one`, against an obstacle moving at
  // `obstacle` (relative to this body's frame), with the loss `loss_J`.
  auto book = [&](DeformableBody& one, const std::array<uint32_t, 3>& k, const Eigen::Vector3d& w,
                  const Eigen::Vector3d& j, const Eigen::Vector3d& obstacle, double loss_J) {
    StepReport& rep = one.report_;
    rep.obstacle_work_J += j.dot(obstacle);
    rep.contact_work_J += j.dot(obstacle - one.core_velocity_mps_);
    rep.contact_loss_J += loss_J;
    rep.contact_impulse_Ns += j;
    for (int n = 0; n < 3; ++n)
      if (w[n] != 0)
        rep.contact_moment_Nms += (one.previous_m_[k[n]] - one.settings_->core_m).cross(w[n] * j);
  };
  const Eigen::Vector3d& core_a = a.settings_->core_m;
  for (const Contact& c : ls.contacts) {
    if (c.push_x_h.squaredNorm() == 0) continue;
    const bool point_in_b = c.point_side == 1;
    DeformableBody& pb = point_in_b ? b : a;
    DeformableBody& tb = point_in_b ? a : b;
    const Eigen::Vector3d j_a = c.push_x_h * inv_h;  // on the point side, a's frame
    // b's frame moves relative to a's at V_f(p) = v + w x (p - core_a).
    const Eigen::Vector3d p_prev =
        placeOf(link, point_in_b, pb.previous_m_, c.points, c.point_bary, ls.start_behind_s);
    const Eigen::Vector3d frame_mps = link.velocity_mps + link.angular_velocity_radps.cross(p_prev - core_a);
    const Eigen::Vector3d u_point_own = mean(pb, c.points, c.point_bary);
    const Eigen::Vector3d u_other_own = mean(tb, c.corners, c.bary);
    // Each side's velocity relative to a's frame, in a's frame.
    const Eigen::Vector3d u_point = point_in_b ? Eigen::Vector3d(r * u_point_own + frame_mps) : u_point_own;
    const Eigen::Vector3d u_other = point_in_b ? u_other_own : Eigen::Vector3d(r * u_other_own + frame_mps);
    // To a body's own frame: a vector of a's frame, and a velocity relative to a's frame.
    auto vectorIn = [&](bool in_b, const Eigen::Vector3d& v) {
      return in_b ? Eigen::Vector3d(r.transpose() * v) : v;
    };
    auto velocityIn = [&](bool in_b, const Eigen::Vector3d& u) {
      return in_b ? Eigen::Vector3d(r.transpose() * (u - frame_mps)) : u;
    };
    const double loss_J = -j_a.dot(u_point - u_other);
    ls.report.loss_J += loss_J;
    ls.report.impulse_on_a_Ns += point_in_b ? Eigen::Vector3d(-j_a) : j_a;
    book(pb, c.points, c.point_bary, vectorIn(point_in_b, j_a), velocityIn(point_in_b, u_other), loss_J);
    book(tb, c.corners, c.bary, vectorIn(!point_in_b, -j_a), velocityIn(!point_in_b, u_point), loss_J);
  }
}

std::vector<StepReport> stepGroup(const std::vector<DeformableBody*>& bodies,
                                  const std::vector<const StepInputs*>& inputs,
                                  const std::vector<BodyLink>& links, double dt_s,
                                  std::vector<LinkReport>* link_reports) {
  BodyGroup group(bodies, links, dt_s);
  return group.step(inputs, link_reports);
}

}  // namespace deform
