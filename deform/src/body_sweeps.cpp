// DeformableBody's sweeps (deformable_body.hpp): one Gauss-Seidel pass over the edges, crush columns (or
// spokes) and bends, with their yield forces as multiplier bounds when force-limited, then the obstacles'
// point and face contacts (XPBD, Macklin, Mueller, Chentanez 2016, Algorithm 1, lines 6-12).
#include <deform/constraints.hpp>
#include <deform/deformable_body.hpp>

#include <cmath>

namespace deform {

void DeformableBody::movedBy(uint32_t shape, uint32_t i, const Eigen::Vector3d& dx) {
  // A correction by obstacle `shape` of point `i`: its momentum x h, and the obstacle's work on the point,
  // impulse J = m dx / h against the obstacle's velocity relative to the core.
  const BodySettings& settings = *settings_;
  const double mi = settings.mass_kg[i];
  sub_.contact_push += mi * dx;
  report_.contact_impulse_per_obstacle_Ns[shape] += (mi * (1.0 / h_s_)) * dx;
  const Eigen::Vector3d obstacle_mps = obstacleVelocity(*inputs_, shape, previous_m_[i]);
  sub_.contact_work_x_h += mi * dx.dot(obstacle_mps - core_velocity_mps_);
  sub_.obstacle_work_x_h += mi * dx.dot(obstacle_mps);
  sub_.contact_moment_x_h += (previous_m_[i] - settings.core_m).cross(mi * dx);
}

// The constraint sweeps, with their yield forces as multiplier bounds (force-limited) or without: the
// unlimited sweep reads no yield arrays, so it costs what it did before they existed.
template <bool kLimited>
void DeformableBody::sweepConstraints() {
  const BodySettings& settings = *settings_;
  auto& x = state_.positions_m;
  const auto& w = settings.inverse_mass_per_kg;
  const auto& m = settings.mass_kg;
  const double w_core = core_inverse_mass_per_kg_;
  const double h = h_s_;
  const double inv_h = 1.0 / h;
  const double inv_h2 = inv_h * inv_h;
  const double h2 = h * h;
  const std::size_t edge_count = settings.edges.size(), spoke_count = settings.spokes.size(),
                    bend_count = settings.bends.size();
  const EdgeConstraint* edges = settings.edges.data();
  const SpokeConstraint* spokes = settings.spokes.data();
  const BendConstraint* bends = settings.bends.data();
  const double* edge_rest = state_.edge_rest_m.data();
  const double* spoke_rest = state_.spoke_rest_m.data();
  const double* bend_rest = state_.bend_rest_m.data();
  const YieldForce* edge_yield = edge_yield_N_.data();
  const YieldForce* spoke_yield = spoke_yield_N_.data();
  const YieldForce* bend_yield = bend_yield_N_.data();
  const Eigen::Vector3d* anchors = settings.spoke_anchor_m.data();
  const bool anchored = settings.anchored_columns;
  const Eigen::Vector3d* column_rest = state_.column_rest_m.data();
  const Eigen::Vector3d* normals = settings.spoke_normal.data();
  const YieldLimits* spoke_limits = settings.spoke_yield.data();
  Eigen::Vector3d& core = sub_.core;
  Eigen::Vector3d& spoke_twist = sub_.spoke_twist;
  for (std::size_t k = 0; k < edge_count; ++k) {
    const EdgeConstraint& c = edges[k];
    projectDistance(x[c.a], x[c.b], w[c.a], w[c.b], edge_rest[k], c.compliance_m_per_N * inv_h2,
                    edge_lambda_[k], kLimited ? -h2 * edge_yield[k].stretch_N : -HUGE_VAL,
                    kLimited ? h2 * edge_yield[k].shorten_N : HUGE_VAL);
  }
  // The core is heavy: every spoke of a sweep sees it where the sweep began, and its corrections are
  // summed and applied after the sweep (Jacobi for the core, Gauss-Seidel for the points), which keeps
  // the sweep free of a chain through one shared position. Momentum is exchanged exactly either way.
  // The summed move is the sum of each constraint's share of its correction; where the shares add up to
  // S > 1 (a shell heavier than its core: distributeMass's own split gives S = 3) it overshoots by up to
  // S, and diverges under a hard push. Each constraint then sees the core heavier, w'_core = S w_core +
  // (S - 1) w_point, so that its share is 1/S of what it was and the core moves by the shares' weighted
  // mean (mass splitting, Tonge, Benevolenski, Voroshilov 2012), still by the exact reaction of the
  // points' moves. A car's shell is a third of its core (S < 1/3): untouched.
  const double split = core_share_sum_;
  auto coreSeenBy = [&](uint32_t i) { return split > 1 ? split * w_core + (split - 1) * w[i] : w_core; };
  Eigen::Vector3d sweep_pull{0, 0, 0};
  if (anchored) {  // crush columns, or spokes below
    // Crush columns: each holds its point at its rest place, which moves with the core.
    const Eigen::Vector3d shift = core - settings.core_m;
    for (std::size_t k = 0; k < spoke_count; ++k) {
      const SpokeConstraint& c = spokes[k];
      const uint32_t i = c.point;
      const Eigen::Vector3d before = x[i];
      const Eigen::Vector3d& rest = column_rest[k];
      const double alpha_tilde = c.compliance_m_per_N * inv_h2;
      if constexpr (kLimited) {
        const double taken = column_taken_m_[k];    // what hardening has added to its yield, and whether it
        const bool bottomed = column_bottomed_[k];  // has crushed to its clamp (refreshColumn)
        const double to_lambda = h2 / c.compliance_m_per_N;
        projectColumn(
            x[i], rest + shift, w[i], coreSeenBy(i), alpha_tilde, column_lambda_[k],
            [&](const Eigen::Vector3d& push) {
              // The column pushes along lambda: its point is displaced along -lambda.
              if (bottomed && normals[k].dot(push) > 0) return HUGE_VAL;
              return to_lambda * columnYield_m(normals[k], -push, spoke_limits[k], taken);
            },
            [&](const Eigen::Vector3d& next) {
              return columnSurelyWithinLimit(normals[k], next, spoke_limits[k], to_lambda, bottomed);
            });
      } else {
        projectColumn(x[i], rest + shift, w[i], coreSeenBy(i), alpha_tilde, column_lambda_[k], nullptr);
      }
      const Eigen::Vector3d pull = m[i] * (x[i] - before);
      sweep_pull += pull;
      spoke_twist += (rest - settings.core_m).cross(pull);
    }
  }
  for (std::size_t k = 0; !anchored && k < spoke_count; ++k) {
    const SpokeConstraint& c = spokes[k];
    const Eigen::Vector3d before = x[c.point];
    Eigen::Vector3d anchor = core + anchors[k];
    projectSpoke(x[c.point], anchor, w[c.point], coreSeenBy(c.point), spoke_rest[k],
                 c.compliance_m_per_N * inv_h2, spoke_lambda_[k],
                 kLimited ? -h2 * spoke_yield[k].stretch_N : -HUGE_VAL,
                 kLimited ? h2 * spoke_yield[k].shorten_N : HUGE_VAL);
    const Eigen::Vector3d pull = m[c.point] * (x[c.point] - before);
    sweep_pull += pull;
    spoke_twist += anchors[k].cross(pull);
  }
  sub_.spoke_pull_Ns += sweep_pull;
  core -= w_core * sweep_pull;
  for (std::size_t k = 0; k < bend_count; ++k) {
    const BendConstraint& c = bends[k];
    projectDistance(x[c.left], x[c.right], w[c.left], w[c.right], bend_rest[k], c.compliance_m_per_N * inv_h2,
                    bend_lambda_[k], kLimited ? -h2 * bend_yield[k].stretch_N : -HUGE_VAL,
                    kLimited ? h2 * bend_yield[k].shorten_N : HUGE_VAL);
  }
}

void DeformableBody::iterate() {
  auto& x = state_.positions_m;
  const auto& w = settings_->inverse_mass_per_kg;
  if (params_.yield_limited)
    sweepConstraints<true>();
  else
    sweepConstraints<false>();
  for (ContactPoint& c : contacts_) {
    const Eigen::Vector3d before = x[c.point];
    // Friction holds the point to the obstacle's surface, which moves (and turns) in this frame.
    projectContact(x[c.point], c.carried_start_m, c.normal, c.surface_m, inputs_->contact_friction);
    c.moved_m += x[c.point] - before;
    movedBy(c.shape, c.point, x[c.point] - before);
  }
  for (FaceContact& c : face_contacts_) {
    const auto& k = c.corners;
    const double inverse_mass[3] = {w[k[0]], w[k[1]], k[2] == k[0] ? 0.0 : w[k[2]]};
    const Eigen::Vector3d before[3] = {x[k[0]], x[k[1]], x[k[2]]};
    projectFaceContact(x[k[0]], x[k[1]], x[k[2]], inverse_mass, c.bary, c.normal, c.surface_m);
    for (int j = 0; j < (k[2] == k[0] ? 2 : 3); ++j) {
      c.moved_m[j] += x[k[j]] - before[j];
      movedBy(c.shape, k[j], x[k[j]] - before[j]);
    }
  }
}

}  // namespace deform
