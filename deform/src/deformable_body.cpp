// The XPBD step of a deformable body (Macklin, Mueller, Chentanez 2016, Algorithm 1, with the
// substepping of Macklin et al. 2019, "Small Steps in Physics Simulation", Algorithm 1).
#include <deform/deformable_body.hpp>
#include <deform/error.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "body_halves.hpp"
#include "prediction.hpp"
#include "shell_wide.hpp"
#include "sweep_wide.hpp"

namespace deform {
namespace {

void checkSizes(const BodySettings& settings, const BodyState& state) {
  if (state.positions_m.size() != settings.pointCount() ||
      state.velocities_mps.size() != settings.pointCount() ||
      state.edge_rest_m.size() != settings.edges.size() ||
      state.spoke_rest_m.size() != settings.spokes.size() ||
      state.bend_rest_m.size() != settings.bends.size() ||
      state.column_rest_m.size() != settings.spokes.size())
    throw InputError("body state: sizes do not match the body settings");
}

}  // namespace

DeformableBody::DeformableBody(std::shared_ptr<const BodySettings> settings, const SolverParams& params)
    : settings_(std::move(settings)), params_(params) {
  if (!settings_) throw InputError("body settings: missing");
  checkSolverParams(params_);
  state_ = restState(*settings_);
  previous_m_.resize(settings_->pointCount());
  edge_lambda_.resize(settings_->edges.size());
  spoke_lambda_.resize(settings_->spokes.size());
  column_lambda_.resize(settings_->spokes.size());
  bend_lambda_.resize(settings_->bends.size());
  for (double r : settings_->spoke_rest_m) radius_m_ = std::max(radius_m_, r);
  edge_pairs_ = interleavedPairs(
      settings_->edges, [](const EdgeConstraint& c) { return c.a; },
      [](const EdgeConstraint& c) { return c.b; });
  bend_pairs_ = interleavedPairs(
      settings_->bends, [](const BendConstraint& c) { return c.left; },
      [](const BendConstraint& c) { return c.right; });
  edge_disjoint_ = disjointRuns(edge_pairs_);
  bend_disjoint_ = disjointRuns(bend_pairs_);
  columns_in_point_order_ = true;
  for (std::size_t k = 0; k < settings_->spokes.size(); ++k)
    columns_in_point_order_ = columns_in_point_order_ && settings_->spokes[k].point == k;
  refreshYieldForces();
}

void DeformableBody::setState(BodyState state) {
  checkSizes(*settings_, state);
  state_ = std::move(state);
  rigid_moments_.valid = false;
  refreshYieldForces();
}

void DeformableBody::refreshYieldForces() {
  const BodySettings& s = *settings_;
  const auto& laws = s.plastic_laws;
  edge_band_.resize(s.edges.size());
  spoke_band_.resize(s.spokes.size());
  bend_band_.resize(s.bends.size());
  for (std::size_t k = 0; k < s.edges.size(); ++k)
    edge_band_[k] =
        elasticBand(state_.edge_rest_m[k], s.edge_rest_m[k], s.edge_yield[k], laws[s.edges[k].material]);
  for (std::size_t k = 0; k < s.spokes.size(); ++k)
    spoke_band_[k] =
        elasticBand(state_.spoke_rest_m[k], s.spoke_rest_m[k], s.spoke_yield[k], laws[s.spokes[k].material]);
  for (std::size_t k = 0; k < s.bends.size(); ++k)
    bend_band_[k] =
        elasticBand(state_.bend_rest_m[k], s.bend_rest_m[k], s.bend_yield[k], laws[s.bends[k].material]);
  column_taken_m_.resize(s.spokes.size());
  column_bottomed_.resize(s.spokes.size());
  for (std::size_t k = 0; k < s.spokes.size(); ++k) refreshColumn(k);
  edge_yield_N_.resize(s.edges.size());
  spoke_yield_N_.resize(s.spokes.size());
  bend_yield_N_.resize(s.bends.size());
  if (!params_.yield_limited) {  // unlimited: the solver may carry any force, plasticity follows
    std::fill(edge_yield_N_.begin(), edge_yield_N_.end(), YieldForce{});
    std::fill(spoke_yield_N_.begin(), spoke_yield_N_.end(), YieldForce{});
    std::fill(bend_yield_N_.begin(), bend_yield_N_.end(), YieldForce{});
    return;
  }
  for (std::size_t k = 0; k < s.edges.size(); ++k)
    edge_yield_N_[k] = yieldForce(s.edges[k].compliance_m_per_N, state_.edge_rest_m[k], s.edge_rest_m[k],
                                  s.edge_yield[k], laws[s.edges[k].material]);
  for (std::size_t k = 0; k < s.spokes.size(); ++k)
    spoke_yield_N_[k] = yieldForce(s.spokes[k].compliance_m_per_N, state_.spoke_rest_m[k], s.spoke_rest_m[k],
                                   s.spoke_yield[k], laws[s.spokes[k].material]);
  for (std::size_t k = 0; k < s.bends.size(); ++k)
    bend_yield_N_[k] = yieldForce(s.bends[k].compliance_m_per_N, state_.bend_rest_m[k], s.bend_rest_m[k],
                                  s.bend_yield[k], laws[s.bends[k].material]);
}

Eigen::Vector3d DeformableBody::heldBack(uint32_t shape, Eigen::Vector3d v) const {
  // Against each held normal in turn, a few rounds (two holders at an angle, a box in a corner).
  for (int round = 0; round < 3; ++round)
    for (const Eigen::Vector3d& n : obstacle_held_[shape]) {
      const double into = n.dot(v);
      if (into < 0) v -= into * n;
    }
  return v;
}

Eigen::Vector3d DeformableBody::heldMove(uint32_t shape, const Eigen::Vector3d& move_m) const {
  if (obstacle_held_[shape].empty()) return move_m;
  // The obstacle's displacement off its path (which its holders already shaped) stays out of them.
  const Eigen::Vector3d now = obstacle_offset_m_[shape] + obstacle_shift_m_[shape];
  return heldBack(shape, now + move_m) - now;
}

void DeformableBody::refreshColumn(std::size_t k) {
  const BodySettings& s = *settings_;
  const SpokeConstraint& c = s.spokes[k];
  const Eigen::Vector3d& rest = state_.column_rest_m[k];
  const Eigen::Vector3d& original = s.rest_positions_m[c.point];
  const PlasticLaw& law = s.plastic_laws[c.material];
  column_taken_m_[k] = law.hardening * (rest - original).norm();
  // Crushed to its clamp, a column can flow no further in: it bottoms out, rigidly elastic (as yieldForce
  // for a spoke).
  column_bottomed_[k] = s.spoke_normal[k].dot(original - rest) >=
                        (1.0 - law.min_rest_fraction) * s.spoke_rest_m[k] * (1 - 1e-12);
}

void DeformableBody::setParams(const SolverParams& params) {
  checkSolverParams(params);
  params_ = params;
  refreshYieldForces();
}

bool DeformableBody::loadChanged() const {
  // Bound on the change of the inertial acceleration at the furthest control point (radius R):
  // |d(g - a_c)| + |d alpha| R + |d omega| (|omega_0| + |omega_1|) R, scaled.
  const BodyState& s = state_;
  const double change = (load_mps2_ - s.sleep_load_mps2).norm() +
                        (alpha_radps2_ - s.sleep_angular_acceleration_radps2).norm() * radius_m_ +
                        (omega_radps_ - s.sleep_angular_velocity_radps).norm() *
                            (omega_radps_.norm() + s.sleep_angular_velocity_radps.norm()) * radius_m_;
  return params_.inertial_scale * change > params_.wake_load_mps2;
}

StepReport DeformableBody::step(const StepInputs& inputs, double dt_s) {
  if (beginStep(inputs, dt_s, false)) {
    for (uint32_t k = 1; k <= substeps_; ++k) {
      beginSubstep(k);
      for (uint32_t it = 0; it < params_.iterations; ++it) iterate();
      settleSubstep();
      endSubstep();
    }
  }
  return endStep();
}

bool DeformableBody::beginStep(const StepInputs& inputs, double dt_s, bool touched) {
  if (!std::isfinite(dt_s) || dt_s <= 0)
    throw InputError("dt_s: time step must be finite and > 0 (got " + std::to_string(dt_s) + " s)");
  const BodySettings& settings = *settings_;
  for (std::size_t k = 0; k < inputs.impulses.size(); ++k) {
    const PointImpulse& impulse = inputs.impulses[k];
    const std::string field = "impulses[" + std::to_string(k) + "]";
    if (impulse.point >= settings.pointCount()) throw InputError(field + ".point: no such control point");
    if (!impulse.impulse_Ns.allFinite()) throw InputError(field + ".impulse_Ns: not finite");
  }
  for (std::size_t k = 0; k < inputs.contacts.size(); ++k)
    checkContactShape(inputs.contacts[k], ("contacts[" + std::to_string(k) + "]").c_str());
  for (std::size_t k = 0; k < inputs.contact_velocity_mps.size(); ++k)
    if (!inputs.contact_velocity_mps[k].allFinite())
      throw InputError("contact_velocity_mps[" + std::to_string(k) + "]: not finite");
  for (std::size_t k = 0; k < inputs.contact_angular_velocity_radps.size(); ++k)
    if (!inputs.contact_angular_velocity_radps[k].allFinite())
      throw InputError("contact_angular_velocity_radps[" + std::to_string(k) + "]: not finite");
  for (std::size_t k = 0; k < inputs.contact_held_normals.size(); ++k)
    for (const Eigen::Vector3d& n : inputs.contact_held_normals[k])
      if (!n.allFinite() || !(n.norm() > 0))
        throw InputError("contact_held_normals[" + std::to_string(k) + "]: not a finite, non-zero normal");
  for (std::size_t k = 0; k < inputs.contact_inverse_mass_per_kg.size(); ++k)
    if (!std::isfinite(inputs.contact_inverse_mass_per_kg[k]) || inputs.contact_inverse_mass_per_kg[k] < 0)
      throw InputError("contact_inverse_mass_per_kg[" + std::to_string(k) + "]: must be finite and >= 0");
  {
    // A rotation: orthonormal within rounding, determinant +1 (the obstacles' moves are turned by it).
    const Eigen::Matrix3d& r = inputs.frame_to_world;
    if (!r.allFinite() || !((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-6) ||
        !(r.determinant() > 0))
      throw InputError("frame_to_world: not a rotation matrix");
  }
  if (std::isnan(inputs.core_mass_kg) || !(inputs.core_mass_kg > 0))
    throw InputError("core_mass_kg: must be > 0 (infinite: a kinematic core)");
  if (!inputs.core_inverse_inertia_per_kg_m2.allFinite() || !inputs.core_centre_of_mass_m.allFinite())
    throw InputError("core_inverse_inertia_per_kg_m2, core_centre_of_mass_m: must be finite");
  if (!std::isfinite(inputs.contact_friction) || inputs.contact_friction < 0)
    throw InputError("contact_friction: must be finite and >= 0 (got " +
                     std::to_string(inputs.contact_friction) + ")");
  const ChassisMotion& chassis = inputs.chassis;
  if (!chassis.acceleration_mps2.allFinite() || !chassis.angular_velocity_radps.allFinite() ||
      !chassis.angular_acceleration_radps2.allFinite() || !chassis.gravity_mps2.allFinite())
    throw InputError("chassis: motion not finite");
  load_mps2_ = chassis.gravity_mps2 - chassis.acceleration_mps2;
  omega_radps_ = chassis.angular_velocity_radps;
  alpha_radps2_ = chassis.angular_acceleration_radps2;
  inputs_ = &inputs;
  dt_s_ = dt_s;

  report_ = StepReport{};
  stop_omega_radps_.setZero();
  report_.contact_impulse_per_obstacle_Ns.assign(inputs.contacts.size(), Eigen::Vector3d::Zero());
  report_.obstacle_displacement_m.assign(inputs.contacts.size(), Eigen::Vector3d::Zero());
  report_.obstacle_velocity_change_mps.assign(inputs.contacts.size(), Eigen::Vector3d::Zero());
  obstacle_inverse_mass_.assign(inputs.contacts.size(), 0.0);
  for (std::size_t k = 0; k < inputs.contacts.size() && k < inputs.contact_inverse_mass_per_kg.size(); ++k)
    obstacle_inverse_mass_[k] = inputs.contact_inverse_mass_per_kg[k];
  obstacle_offset_m_.assign(inputs.contacts.size(), Eigen::Vector3d::Zero());
  obstacle_dv_mps_.assign(inputs.contacts.size(), Eigen::Vector3d::Zero());
  obstacle_shift_m_.assign(inputs.contacts.size(), Eigen::Vector3d::Zero());
  obstacle_held_.assign(inputs.contacts.size(), {});
  for (std::size_t k = 0; k < inputs.contacts.size() && k < inputs.contact_held_normals.size(); ++k)
    for (const Eigen::Vector3d& n : inputs.contact_held_normals[k])
      obstacle_held_[k].push_back(n.normalized());
  bool load_changed = false;
  if (state_.sleeping) {
    load_changed = loadChanged();
    if (inputs.contacts.empty() && inputs.impulses.empty() && !load_changed && !touched) {
      report_.asleep = true;
      state_.time_s += dt_s;
      rigidShellLoad(dt_s, inputs.core_mass_kg, report_);
      return false;
    }
    state_.sleeping = false;
    rigid_moments_.valid = false;
    if (load_changed || !inputs.impulses.empty()) state_.sleep_timer_s = 0;
  }

  for (const PointImpulse& impulse : inputs.impulses)
    state_.velocities_mps[impulse.point] += impulse.impulse_Ns * settings.inverse_mass_per_kg[impulse.point];

  core_inverse_mass_per_kg_ = std::isfinite(inputs.core_mass_kg) ? 1.0 / inputs.core_mass_kg : 0.0;
  // How far the core's summed reactions would overshoot (sweepConstraints, beginSubstep's drag): a
  // function of the masses alone, found again only when the core's mass changes.
  if (!(inputs.core_mass_kg == overshoot_core_mass_kg_)) {
    overshoot_core_mass_kg_ = inputs.core_mass_kg;
    core_share_sum_ = 0;
    double shell_kg = 0;
    if (core_inverse_mass_per_kg_ > 0) {
      for (const SpokeConstraint& c : settings.spokes)
        core_share_sum_ +=
            core_inverse_mass_per_kg_ / (settings.inverse_mass_per_kg[c.point] + core_inverse_mass_per_kg_);
      for (double m : settings.mass_kg) shell_kg += m;
    }
    drag_split_ = std::max(1.0, core_inverse_mass_per_kg_ * shell_kg);
  }
  core_shift_m_.setZero();
  core_velocity_mps_.setZero();
  substeps_ = inputs.contacts.empty()
                  ? params_.substeps
                  : substepsNoLongerThan(dt_s, params_.substeps, params_.longest_contact_substep_s);
  h_s_ = dt_s / static_cast<double>(substeps_);
  return true;
}

StepReport DeformableBody::endStep() {
  const BodySettings& settings = *settings_;
  const StepInputs& inputs = *inputs_;
  StepReport report = std::move(report_);
  report_ = StepReport{};
  inputs_ = nullptr;
  if (report.asleep) return report;
  const double dt_s = dt_s_;
  last_substep_s_ = h_s_;
  carried_elastic_J_ = -1;  // the multipliers changed
  state_.time_s += dt_s;
  // Re-centre on the core: positions and velocities stay relative to it; the caller moves its rigid body.
  report.core_displacement_m = core_shift_m_;
  for (std::size_t j = 0; j < obstacle_inverse_mass_.size(); ++j)
    if (obstacle_inverse_mass_[j] > 0) {
      report.obstacle_displacement_m[j] = obstacle_offset_m_[j];
      report.obstacle_velocity_change_mps[j] = obstacle_dv_mps_[j];
    }
  report.core_velocity_mps = core_velocity_mps_;
  if (core_inverse_mass_per_kg_ > 0)
    for (std::size_t i = 0; i < settings.pointCount(); ++i) {
      state_.positions_m[i] -= core_shift_m_;
      state_.velocities_mps[i] -= core_velocity_mps_;
    }

  // Sleep bookkeeping.
  double max_speed2 = 0;
  for (const Eigen::Vector3d& v : state_.velocities_mps) max_speed2 = std::max(max_speed2, v.squaredNorm());
  report.max_speed_mps = std::sqrt(max_speed2);
  const bool quiet =
      report.contact_points == 0 && inputs.impulses.empty() && report.max_speed_mps < params_.sleep_speed_mps;
  state_.sleep_timer_s = quiet ? state_.sleep_timer_s + dt_s : 0.0;
  if (quiet && params_.sleep_delay_s >= 0 && state_.sleep_timer_s >= params_.sleep_delay_s) {
    state_.sleeping = true;
    rigid_moments_.valid = false;
    for (Eigen::Vector3d& v : state_.velocities_mps) v.setZero();
    state_.sleep_load_mps2 = load_mps2_;
    state_.sleep_angular_velocity_radps = omega_radps_;
    state_.sleep_angular_acceleration_radps2 = alpha_radps2_;
  }
  return report;
}

double DeformableBody::carriedElasticEnergy_J() const {
  if (!(last_substep_s_ > 0)) return 0;
  if (carried_elastic_J_ >= 0) return carried_elastic_J_;
  const BodySettings& s = *settings_;
  const double inv_h2 = 1.0 / (last_substep_s_ * last_substep_s_);
  double energy_J = 0;
  auto add = [&](double compliance_m_per_N, double lambda) {
    const double force_N = lambda * inv_h2;
    energy_J += 0.5 * compliance_m_per_N * force_N * force_N;
  };
  for (std::size_t k = 0; k < s.edges.size(); ++k) add(s.edges[k].compliance_m_per_N, edge_lambda_[k]);
  if (s.anchored_columns)
    for (std::size_t k = 0; k < s.spokes.size(); ++k)
      add(s.spokes[k].compliance_m_per_N, column_lambda_[k].norm());
  else
    for (std::size_t k = 0; k < s.spokes.size(); ++k) add(s.spokes[k].compliance_m_per_N, spoke_lambda_[k]);
  for (std::size_t k = 0; k < s.bends.size(); ++k) add(s.bends[k].compliance_m_per_N, bend_lambda_[k]);
  carried_elastic_J_ = energy_J;
  return energy_J;
}

void DeformableBody::rigidShellLoad(double dt_s, double core_mass_kg, StepReport& report) {
  // A sleeping shell moves with its core as one rigid body: the spokes hold every point against its
  // inertial load a_i = load - alpha x r_i - omega x (omega x r_i) (v = 0), so the core takes
  //   impulse = dt (M load' - alpha x S - omega x (omega x S)),
  //   moment  = dt (S x load' - I alpha - omega x (I omega)),
  // with M, S = sum m r and I = sum m (|r|^2 E - r r^T) of the frozen shell about the core. A core of
  // finite mass M_c is carried along by the shell as an awake body's is (the substeps' free core): the
  // two accelerate together by M load / (M_c + M), which leaves the points load' = M_c / (M_c + M) load
  // to hold. (A kinematic core: load' = load.)
  if (params_.inertial_scale <= 0) return;
  if (!rigid_moments_.valid) {
    const BodySettings& settings = *settings_;
    RigidMoments moments;
    for (std::size_t i = 0; i < settings.pointCount(); ++i) {
      const Eigen::Vector3d r = state_.positions_m[i] - settings.core_m;
      const double m = settings.mass_kg[i];
      moments.mass_kg += m;
      moments.first_moment_kgm += m * r;
      moments.inertia_kgm2 += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    moments.valid = true;
    rigid_moments_ = moments;
  }
  const RigidMoments& m = rigid_moments_;
  const double scale = params_.inertial_scale * dt_s;
  const double carried = std::isfinite(core_mass_kg) ? core_mass_kg / (core_mass_kg + m.mass_kg) : 1.0;
  const Eigen::Vector3d load = carried * load_mps2_;
  const Eigen::Vector3d& s = m.first_moment_kgm;
  report.core_impulse_Ns +=
      scale * (m.mass_kg * load - alpha_radps2_.cross(s) - omega_radps_.cross(omega_radps_.cross(s)));
  report.core_angular_impulse_Nms += scale * (s.cross(load) - m.inertia_kgm2 * alpha_radps2_ -
                                              omega_radps_.cross(m.inertia_kgm2 * omega_radps_));
}

void DeformableBody::beginSubstep(uint32_t k) {
  const BodySettings& settings = *settings_;
  const StepInputs& inputs = *inputs_;
  StepReport& report = report_;
  const double h = h_s_;
  // A movable obstacle goes on at its changed velocity (its prediction, as the core's); its shift is zero
  // here (beginStep, endSubstep).
  for (std::size_t j = 0; j < obstacle_inverse_mass_.size(); ++j)
    if (obstacle_inverse_mass_[j] > 0) obstacle_offset_m_[j] += h * obstacle_dv_mps_[j];
  placeObstacles(inputs, static_cast<double>(substeps_ - k) * h);
  const std::size_t n = settings.pointCount();
  auto& x = state_.positions_m;
  auto& v = state_.velocities_mps;
  const auto& m = settings.mass_kg;
  const double w_core = core_inverse_mass_per_kg_;
  // The core inside the substep: at core_m + shift, moving at core_velocity (relative to its kinematic
  // path). Every correction that ties a point to it pushes it back (momentum exchanged, `to_core`).
  sub_ = SubstepSums{};
  Eigen::Vector3d& core = sub_.core;
  core = settings.core_m + core_shift_m_;
  Eigen::Vector3d& to_core_Ns = sub_.to_core_Ns;

  // Prediction: exact viscous decay of the motion relative to the core (its reaction on the core),
  // explicit velocity update with the inertial forces, then positions.
  const double scale = params_.inertial_scale;
  // Each point's drag acts in full and the core takes the summed reaction (Jacobi for the core): on a shell
  // heavier than its core (drag_split_ > 1) that sum overshoots, so each point takes 1 / drag_split_ of
  // its drag, and the core moves by the reactions' mass-weighted mean (as the columns, sweepConstraints).
  const double full_decay = std::exp(-params_.damping_per_s * h);
  const double decay = drag_split_ > 1 ? 1.0 + (full_decay - 1.0) / drag_split_ : full_decay;
  const bool inertial = scale > 0 && (load_mps2_.squaredNorm() > 0 || omega_radps_.squaredNorm() > 0 ||
                                      alpha_radps2_.squaredNorm() > 0);
  // The two halves of the points side by side (SolverParams::threads), each with its own sums.
  Prediction prediction;
  prediction.x = x.data();
  prediction.previous = previous_m_.data();
  prediction.v = v.data();
  prediction.mass_kg = m.data();
  prediction.max_deviation_m = settings.max_deviation_m.data();
  prediction.core_m = core;
  prediction.core_velocity_mps = core_velocity_mps_;
  prediction.load_mps2 = load_mps2_;
  prediction.omega_radps = omega_radps_;
  prediction.alpha_radps2 = alpha_radps2_;
  prediction.h_s = h;
  prediction.decay = decay;
  prediction.inertial_scale = scale;
  prediction.inertial = inertial;
  // Each half also clears the edges' and bends' multipliers its sweep writes (those across the cut with
  // half 0), so on two threads they are in the cache of the thread that uses them, and the columns' (or
  // spokes') by index, which is near the sweep's halves (BodySettings::column_order): Gauss-Seidel sweeps,
  // each constraint kind in its own loop, whose multipliers start at zero each substep.
  PredictionSums sums[2];
  forEachHalf(params_.threads, [&](int half) {
    PredictionSums sum;  // a local, stored once: the two halves' sums share a cache line
    const auto [begin, end] = halfOf(n, half);
    predictPoints(prediction, begin, end, params_.wide_sweep, sum);
    sums[half] = sum;
    clearMultipliers(half);
  });
  for (const PredictionSums& sum : sums) {
    report.damping_loss_J += sum.damping_loss_J;
    report.inertial_work_J += sum.inertial_work_J;
    to_core_Ns += sum.to_core_Ns;
  }
  core_velocity_mps_ += w_core * to_core_Ns;
  sub_.core_start = core;
  core += h * core_velocity_mps_;

  report.contact_points += findContacts(placed_, inputs, h);
}

void DeformableBody::clearMultipliers(int half) {
  const BodySettings& settings = *settings_;
  const auto clear = [half](auto& lambda, const std::array<uint32_t, 2>& half_end) {
    using Value = typename std::decay_t<decltype(lambda)>::value_type;
    const auto begin = lambda.begin();
    if (half == 0) {
      std::fill(begin, begin + half_end[0], Value{});
      std::fill(begin + half_end[1], lambda.end(), Value{});
    } else {
      std::fill(begin + half_end[0], begin + half_end[1], Value{});
    }
  };
  clear(edge_lambda_, settings.edge_half_end);
  clear(bend_lambda_, settings.bend_half_end);
  const auto [begin, end] = halfOf(settings.spokes.size(), half);
  if (settings.anchored_columns)
    std::fill(column_lambda_.begin() + begin, column_lambda_.begin() + end, Eigen::Vector3d::Zero());
  else
    std::fill(spoke_lambda_.begin() + begin, spoke_lambda_.begin() + end, 0.0);
}

void DeformableBody::settleSubstep() {
  const BodySettings& settings = *settings_;
  const double h = h_s_;
  const double inv_h = 1.0 / h;
  const double w_core = core_inverse_mass_per_kg_;
  Eigen::Vector3d& core = sub_.core;
  Eigen::Vector3d& tie_push = sub_.tie_push;
  // The shell stays bolted to the chassis: no rotation of the whole shell about the core, whose
  // reaction is the opposite of the shell's angular impulse; and the spokes pull at their anchors, off
  // the core: the moment of their reaction on it.
  const Eigen::Vector3d shift = core - settings.core_m;
  // The shell orientation constraint (shellRotation, turnShell), the points in two halves
  // (SolverParams::threads), each half's sums its own.
  Eigen::Vector3d* x = state_.positions_m.data();
  const Eigen::Vector3d* x0 = settings.rest_positions_m.data();
  const double* m = settings.mass_kg.data();
  const std::size_t n = settings.pointCount();
  Eigen::Vector3d moment[2], given[2], pushed[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  forEachHalf(params_.threads, [&](int half) {
    const auto [begin, end] = halfOf(n, half);
    moment[half] = shellRotationWide(x + begin, x0 + begin, m + begin, end - begin, settings.core_m, shift,
                                     params_.wide_sweep);
  });
  const Eigen::Vector3d mu = -(settings.shell_inverse_inertia * (moment[0] + moment[1]));
  forEachHalf(params_.threads, [&](int half) {
    const auto [begin, end] = halfOf(n, half);
    Eigen::Vector3d push{0, 0, 0};  // a local, stored once (as the prediction's sums)
    given[half] = turnShellWide(x + begin, x0 + begin, m + begin, end - begin, settings.core_m, shift, mu,
                                push, params_.wide_sweep);
    pushed[half] = push;
  });
  tie_push += pushed[0];
  tie_push += pushed[1];
  const Eigen::Vector3d shell_defect = -(given[0] + given[1]);
  report_.core_angular_impulse_Nms += (shell_defect - sub_.spoke_twist) * inv_h;

  // Visual constraint, the last projection of the substep (Kenwright 2015, "Visual Constraints").
  core -= w_core * tie_push;
  capDeviation(h, *inputs_, core, sub_.core_start, tie_push, report_);

  plasticity(report_, core, h);
  report_.contact_loss_J += contactLoss(*inputs_, h);
}

void DeformableBody::endSubstep() {
  const BodySettings& settings = *settings_;
  const std::size_t n = settings.pointCount();
  auto& x = state_.positions_m;
  auto& v = state_.velocities_mps;
  const double inv_h = 1.0 / h_s_;
  StepReport& report = report_;
  // Velocities from positions (Verlet style; XPBD Algorithm 1, line 16).
  const Eigen::Vector3d* previous = previous_m_.data();
  forEachHalf(params_.threads, [&](int half) {
    const auto [begin, end] = halfOf(n, half);
    // As flat arrays of coordinates, which the compiler vectorises (the same operations per coordinate).
    const double* xs = x[0].data();
    const double* ps = previous[0].data();
    double* vs = v[0].data();
    for (std::size_t j = 3 * begin; j < 3 * end; ++j) vs[j] = (xs[j] - ps[j]) * inv_h;
  });
  // A movable obstacle's velocity from its displacement, as the points' (XPBD Algorithm 1, line 16).
  for (std::size_t j = 0; j < obstacle_inverse_mass_.size(); ++j)
    if (obstacle_inverse_mass_[j] > 0) {
      obstacle_offset_m_[j] += obstacle_shift_m_[j];
      obstacle_dv_mps_[j] =
          heldBack(static_cast<uint32_t>(j), obstacle_dv_mps_[j] + obstacle_shift_m_[j] * inv_h);
      obstacle_shift_m_[j].setZero();
    }
  report.contact_work_J += sub_.contact_work_x_h * inv_h;
  report.obstacle_work_J += sub_.obstacle_work_x_h * inv_h;
  report.contact_moment_Nms += sub_.contact_moment_x_h * inv_h;
  core_velocity_mps_ = (sub_.core - sub_.core_start) * inv_h;
  core_shift_m_ = sub_.core - settings.core_m;
  sub_.to_core_Ns -= (sub_.spoke_pull_Ns + sub_.tie_push) * inv_h;
  report.core_impulse_Ns += sub_.to_core_Ns;
  report.contact_impulse_Ns += sub_.contact_push * inv_h;
}

}  // namespace deform
