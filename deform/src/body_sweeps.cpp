// DeformableBody's sweeps (deformable_body.hpp): one Gauss-Seidel pass over the edges, crush columns (or
// spokes) and bends, with their yield forces as multiplier bounds when force-limited, then the obstacles'
// point and face contacts (XPBD, Macklin, Mueller, Chentanez 2016, Algorithm 1, lines 6-12).
#include <deform/constraints.hpp>
#include <deform/deformable_body.hpp>

#include <omp.h>

#include <cmath>

#include "body_halves.hpp"
#include "columns_wide.hpp"
#include "sweep_wide.hpp"

namespace deform {

void DeformableBody::refreshDistanceFactors() {
  const BodySettings& s = *settings_;
  const auto& w = s.inverse_mass_per_kg;
  const double inv_h2 = 1.0 / (h_s_ * h_s_);
  edge_factors_.resize(s.edges.size());
  for (std::size_t k = 0; k < s.edges.size(); ++k)
    edge_factors_[k] =
        distanceFactors(w[s.edges[k].a], w[s.edges[k].b], s.edges[k].compliance_m_per_N, inv_h2);
  bend_factors_.resize(s.bends.size());
  for (std::size_t k = 0; k < s.bends.size(); ++k)
    bend_factors_[k] =
        distanceFactors(w[s.bends[k].left], w[s.bends[k].right], s.bends[k].compliance_m_per_N, inv_h2);
  // The core is heavy: every column (or spoke) of a sweep sees it where the sweep began, and its corrections
  // are summed and applied after the sweep (Jacobi for the core, Gauss-Seidel for the points), which keeps
  // the sweep free of a chain through one shared position. Momentum is exchanged exactly either way.
  // The summed move is the sum of each constraint's share of its correction; where the shares add up to
  // S > 1 (a shell heavier than its core: distributeMass's own split gives S = 3) it overshoots by up to
  // S, and diverges under a hard push. Each constraint then sees the core heavier, w'_core = S w_core +
  // (S - 1) w_point, so that its share is 1/S of what it was and the core moves by the shares' weighted
  // mean (mass splitting, Tonge, Benevolenski, Voroshilov 2012), still by the exact reaction of the
  // points' moves. A car's shell is a third of its core (S < 1/3): untouched.
  // Hence each column's factors hold the core as it sees it.
  const double w_core = core_inverse_mass_per_kg_, split = core_share_sum_;
  column_factors_.resize(s.spokes.size());
  for (std::size_t k = 0; k < s.spokes.size(); ++k) {
    const double wi = w[s.spokes[k].point];
    column_factors_[k] = distanceFactors(wi, split > 1 ? split * w_core + (split - 1) * wi : w_core,
                                         s.spokes[k].compliance_m_per_N, inv_h2);
  }
  factors_h_s_ = h_s_;
  factors_core_per_kg_ = w_core;
}

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
// unlimited sweep reads no yield arrays, so it costs what it did before they existed. The edges, then
// the columns (or spokes), then the bends; the edges and bends of each half of the body side by side on
// two threads (SolverParams::threads), then those across the cut; the same order on one thread.
template <bool kLimited>
void DeformableBody::sweepConstraints() {
  const BodySettings& settings = *settings_;
  if (!(factors_h_s_ == h_s_ && factors_core_per_kg_ == core_inverse_mass_per_kg_)) refreshDistanceFactors();
  // Raw pointers: the compiler then need not reload a vector's data through `this` in every iteration.
  Eigen::Vector3d* x = state_.positions_m.data();
  const double* w = settings.inverse_mass_per_kg.data();
  const double* m = settings.mass_kg.data();
  double* edge_lambda = edge_lambda_.data();
  double* spoke_lambda = spoke_lambda_.data();
  double* bend_lambda = bend_lambda_.data();
  Eigen::Vector3d* column_lambda = column_lambda_.data();
  const double* column_taken = column_taken_m_.data();
  const uint8_t* column_bottomed = column_bottomed_.data();
  const DistanceFactors* column_factors = column_factors_.data();
  const double w_core = core_inverse_mass_per_kg_;
  const double h = h_s_;
  const double h2 = h * h;
  const std::size_t spoke_count = settings.spokes.size();
  const SpokeConstraint* spokes = settings.spokes.data();
  const double* edge_rest = state_.edge_rest_m.data();
  const double* spoke_rest = state_.spoke_rest_m.data();
  const double* bend_rest = state_.bend_rest_m.data();
  const DistanceFactors* edge_factors = edge_factors_.data();
  const DistanceFactors* bend_factors = bend_factors_.data();
  const YieldForce* edge_yield = edge_yield_N_.data();
  const YieldForce* spoke_yield = spoke_yield_N_.data();
  const YieldForce* bend_yield = bend_yield_N_.data();
  const Eigen::Vector3d* anchors = settings.spoke_anchor_m.data();
  const bool anchored = settings.anchored_columns;
  const Eigen::Vector3d* column_rest = state_.column_rest_m.data();
  const Eigen::Vector3d* normals = settings.spoke_normal.data();
  const YieldLimits* spoke_limits = settings.spoke_yield.data();
  const Eigen::Vector3d core = sub_.core;
  // The edges and bends four at a time where four neighbours share no point (sweep_wide.hpp).
  const bool wide = params_.wide_sweep && wideSweepAvailable();
  const DistanceSweep edge_sweep{
      x, w, edge_pairs_.data(), edge_disjoint_.data(), edge_rest, edge_factors, edge_lambda, edge_yield, h2};
  const DistanceSweep bend_sweep{
      x, w, bend_pairs_.data(), bend_disjoint_.data(), bend_rest, bend_factors, bend_lambda, bend_yield, h2};
  auto sweepEdges = [&](std::size_t begin, std::size_t end) {
    sweepDistances<kLimited>(edge_sweep, begin, end, wide);
  };
  auto sweepBends = [&](std::size_t begin, std::size_t end) {
    sweepDistances<kLimited>(bend_sweep, begin, end, wide);
  };
  // The core moves after the sweep by the columns' summed pull (refreshDistanceFactors says why). Each
  // half of the columns sums its own pull and twist, and the halves are added in order: the same
  // sums on one thread or two.
  using Reaction = ColumnReaction;
  Reaction reaction[2];
  const Eigen::Vector3d shift = core - settings.core_m;
  const uint32_t* column_order = settings.column_order.data();
  ColumnSweep columns;
  columns.x = x;
  columns.w = w;
  columns.mass_kg = m;
  columns.order = column_order;
  columns.spokes = spokes;
  columns.points_in_order = columns_in_point_order_;
  columns.rest_m = column_rest;
  columns.shift_m = shift;
  columns.core_m = settings.core_m;
  columns.factors = column_factors;
  columns.lambda = column_lambda;
  columns.normals = normals;
  columns.limits = spoke_limits;
  columns.taken_m = column_taken;
  columns.bottomed = column_bottomed;
  columns.h2 = h2;
  SpokeSweep spoke_sweep;
  spoke_sweep.x = x;
  spoke_sweep.w = w;
  spoke_sweep.mass_kg = m;
  spoke_sweep.order = column_order;
  spoke_sweep.spokes = spokes;
  spoke_sweep.anchors_m = anchors;
  spoke_sweep.core_m = core;
  spoke_sweep.rest_m = spoke_rest;
  spoke_sweep.factors = column_factors;
  spoke_sweep.lambda = spoke_lambda;
  spoke_sweep.yield = spoke_yield;
  spoke_sweep.h2 = h2;
  auto sweepColumns = [&](std::size_t begin, std::size_t end, Reaction& result) {
    Reaction out;  // a local, stored once: the two halves' sums share a cache line
    // Crush columns: each holds its point at its rest place, which moves with the core (columns_wide.hpp).
    if (anchored)
      deform::sweepColumns<kLimited>(columns, begin, end, wide, out);
    else
      deform::sweepSpokes<kLimited>(spoke_sweep, begin, end, wide, out);
    result = out;
  };
  const auto& edge_end = settings.edge_half_end;
  const auto& bend_end = settings.bend_half_end;
  const std::size_t column_half = settings.column_half_end;
  // Part `half` of the sweep (0 or 1: the halves, side by side; 2: what crosses the cut) of one kind.
  auto edgesOf = [&](int half) {
    if (half < 2)
      sweepEdges(half == 0 ? 0 : edge_end[0], edge_end[static_cast<std::size_t>(half)]);
    else
      sweepEdges(edge_end[1], settings.edges.size());
  };
  auto bendsOf = [&](int half) {
    if (half < 2)
      sweepBends(half == 0 ? 0 : bend_end[0], bend_end[static_cast<std::size_t>(half)]);
    else
      sweepBends(bend_end[1], settings.bends.size());
  };
  auto columnsOf = [&](int half) {
    sweepColumns(half == 0 ? 0 : column_half, half == 0 ? column_half : spoke_count,
                 reaction[half == 0 ? 0 : 1]);
  };
  if (sweepsOnTwoThreads(params_.threads)) {
#pragma omp parallel num_threads(2)
    {
      // One thread per half; one alone (if the runtime gives only one) takes both.
      const int first = omp_get_thread_num(), team = omp_get_num_threads();
      for (int half = first; half < 2; half += team) edgesOf(half);
#pragma omp barrier
#pragma omp single
      edgesOf(2);
      // No barrier between a half's columns and its bends: the other half's touch none of its points.
      for (int half = first; half < 2; half += team) {
        columnsOf(half);
        bendsOf(half);
      }
#pragma omp barrier
      // The end of the team waits for it: no barrier of its own.
#pragma omp single nowait
      bendsOf(2);
    }
  } else {
    for (int half : {0, 1, 2}) edgesOf(half);
    for (int half : {0, 1}) columnsOf(half);
    for (int half : {0, 1, 2}) bendsOf(half);
  }
  const Eigen::Vector3d sweep_pull = reaction[0].pull + reaction[1].pull;
  sub_.spoke_twist += reaction[0].twist + reaction[1].twist;
  sub_.spoke_pull_Ns += sweep_pull;
  sub_.core -= w_core * sweep_pull;
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
    const double w_obstacle = obstacle_inverse_mass_[c.shape];
    if (w_obstacle > 0) {
      // A movable obstacle: the correction is shared by inverse mass, the obstacle moved back by its part
      // (and its surface and the friction's anchor with it).
      Eigen::Vector3d& shift = obstacle_shift_m_[c.shape];
      Eigen::Vector3d corrected = x[c.point];
      projectContact(corrected, c.carried_start_m + shift, c.normal, c.surface_m + shift,
                     inputs_->contact_friction);
      // Its share, as far as what holds it lets it go; the point takes the rest of the correction.
      const Eigen::Vector3d correction = corrected - x[c.point];
      const Eigen::Vector3d moved = heldMove(c.shape, -(w_obstacle / (w[c.point] + w_obstacle)) * correction);
      x[c.point] += correction + moved;
      shift += moved;
    } else {
      projectContact(x[c.point], c.carried_start_m, c.normal, c.surface_m, inputs_->contact_friction);
    }
    c.moved_m += x[c.point] - before;
    movedBy(c.shape, c.point, x[c.point] - before);
  }
  for (FaceContact& c : face_contacts_) {
    const auto& k = c.corners;
    const double inverse_mass[3] = {w[k[0]], w[k[1]], k[2] == k[0] ? 0.0 : w[k[2]]};
    const Eigen::Vector3d before[3] = {x[k[0]], x[k[1]], x[k[2]]};
    const double w_obstacle = obstacle_inverse_mass_[c.shape];
    if (w_obstacle > 0) {
      Eigen::Vector3d& shift = obstacle_shift_m_[c.shape];
      Eigen::Vector3d share{0, 0, 0};
      projectFaceContact(x[k[0]], x[k[1]], x[k[2]], inverse_mass, c.bary, c.normal, c.surface_m + shift,
                         w_obstacle, &share);
      const Eigen::Vector3d moved = heldMove(c.shape, share);
      shift += moved;
      // Held back: the corners take what the obstacle could not.
      if (moved != share)
        projectFaceContact(x[k[0]], x[k[1]], x[k[2]], inverse_mass, c.bary, c.normal, c.surface_m + shift);
    } else {
      projectFaceContact(x[k[0]], x[k[1]], x[k[2]], inverse_mass, c.bary, c.normal, c.surface_m);
    }
    for (int j = 0; j < (k[2] == k[0] ? 2 : 3); ++j) {
      c.moved_m[j] += x[k[j]] - before[j];
      movedBy(c.shape, k[j], x[k[j]] - before[j]);
    }
  }
}

}  // namespace deform
