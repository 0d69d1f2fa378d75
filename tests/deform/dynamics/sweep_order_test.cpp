// The sweep's order (deform/src/sweep_order.hpp) and the two-thread sweep (SolverParams::threads): the
// halves share no point, the order keeps every constraint, neighbours in the sweep rarely share a point,
// the order by level gives the windowed order's bits, and two threads give the bits of one.
#include "fixtures.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/deformable_body.hpp>
#include <sweep_order.hpp>
#include <sweep_wide.hpp>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

using namespace deform;
using namespace dynamics_test;

namespace {

/// Which half each point is swept in (BodySettings::column_order: the first column_half_end points).
std::vector<int> halfOfPoint(const BodySettings& s) {
  std::vector<int> half(s.pointCount(), -1);
  for (std::size_t j = 0; j < s.column_order.size(); ++j)
    half[s.spokes[s.column_order[j]].point] = j < s.column_half_end ? 0 : 1;
  return half;
}

/// Pairs (a, b) of a constraint list, in its order.
template <class C, class Points>
std::vector<std::pair<uint32_t, uint32_t>> pairsOf(const std::vector<C>& list, Points points) {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (const C& c : list) out.push_back(points(c));
  return out;
}

/// Checks that pairs[0 .. end[0]) lie in half 0, pairs[end[0] .. end[1]) in half 1, the rest across.
void checkParts(const std::vector<std::pair<uint32_t, uint32_t>>& pairs, const std::array<uint32_t, 2>& end,
                const std::vector<int>& half) {
  REQUIRE(end[0] <= end[1]);
  REQUIRE(end[1] <= pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const int a = half[pairs[k].first], b = half[pairs[k].second];
    const int part = k < end[0] ? 0 : k < end[1] ? 1 : 2;
    if (part < 2) {
      REQUIRE(a == part);
      REQUIRE(b == part);
    } else {
      REQUIRE(a != b);
    }
  }
}

/// Fraction of neighbours in a list that share a point.
template <class Pairs>
double sharedNeighbours(const Pairs& pairs) {
  std::size_t shared = 0;
  for (std::size_t k = 1; k < pairs.size(); ++k) {
    const auto& [a, b] = pairs[k - 1];
    const auto& [c, d] = pairs[k];
    shared += (a == c || a == d || b == c || b == d) ? 1 : 0;
  }
  return static_cast<double>(shared) / static_cast<double>(pairs.size() - 1);
}

/// The textbook XPBD distance update (Macklin, Mueller, Chentanez 2016, eq. 17, 18), with the quotient:
/// the reference for the sweep's form with the step's factors.
void referenceDistance(Eigen::Vector3d& xa, Eigen::Vector3d& xb, double wa, double wb, double rest_m,
                       double alpha_tilde, double& lambda, double lambda_min, double lambda_max) {
  const Eigen::Vector3d d = xa - xb;
  const double length = d.norm();
  const double c = length - rest_m;
  const double next =
      std::clamp(lambda + (-c - alpha_tilde * lambda) / (wa + wb + alpha_tilde), lambda_min, lambda_max);
  const Eigen::Vector3d n = d * ((next - lambda) / length);
  lambda = next;
  xa += wa * n;
  xb -= wb * n;
}

StepInputs pressed(const BodySettings& s, int step) {
  double front_m = -1e300;
  for (const auto& p : s.rest_positions_m) front_m = std::max(front_m, p.x());
  StepInputs in;
  // A post driven into the front, off the centreline, and a wall behind it.
  const double reach = front_m + 0.2 - 0.004 * std::min(step, 60);
  CylinderShape post;
  post.a_m = {reach, 0.15, s.core_m.z() - 1.0};
  post.b_m = {reach, 0.15, s.core_m.z() + 1.0};
  post.radius_m = 0.08;
  in.contacts.push_back(post);
  in.contacts.push_back(HalfSpaceShape{{-1, 0, 0}, -(front_m + 0.05 - 0.002 * std::min(step, 60))});
  in.chassis.acceleration_mps2 = {-20, 1, 0};
  in.chassis.gravity_mps2 = {0, 0, -9.81};
  if (step % 9 == 0) in.impulses.push_back({static_cast<uint32_t>(step % 50), Eigen::Vector3d(-30, 10, 5)});
  return in;
}

/// The share of constraints the wide sweep takes `length` at a time, given disjointRuns' lengths.
double shareInRuns(const std::vector<uint8_t>& runs, std::size_t length) {
  std::size_t taken = 0;
  for (std::size_t k = 0; k < runs.size();)
    if (runs[k] >= length) {
      taken += length;
      k += length;
    } else {
      ++k;
    }
  return static_cast<double>(taken) / static_cast<double>(runs.size());
}

}  // namespace

TEST_CASE("the sweep keeps every constraint, its halves share no point, and neighbours rarely share one",
          "[dynamics]") {
  const ControlMesh mesh = sedanControlMesh(1000);
  BodyDescription d;
  d.anchored_columns = true;
  const auto settings = makeSettings(mesh, 1500.0, d);
  const BodySettings& s = *settings;
  const std::vector<int> half = halfOfPoint(s);
  // Every point in one half; the halves hold n / 2 and n - n / 2 points.
  REQUIRE(std::count(half.begin(), half.end(), -1) == 0);
  CHECK(s.column_half_end == s.pointCount() / 2);
  std::vector<uint32_t> columns = s.column_order;
  std::sort(columns.begin(), columns.end());
  for (uint32_t k = 0; k < columns.size(); ++k) REQUIRE(columns[k] == k);

  const auto edges = pairsOf(s.edges, [](const EdgeConstraint& e) { return std::pair{e.a, e.b}; });
  const auto bends = pairsOf(s.bends, [](const BendConstraint& b) { return std::pair{b.left, b.right}; });
  checkParts(edges, s.edge_half_end, half);
  checkParts(bends, s.bend_half_end, half);
  // The same edges as the mesh's, once each, and the rest lengths moved with them.
  std::set<std::pair<uint32_t, uint32_t>> swept(edges.begin(), edges.end()), meshed;
  for (const ControlEdge& e : mesh.edges) meshed.insert({e.a, e.b});
  CHECK(swept == meshed);
  CHECK(edges.size() == mesh.edges.size());
  for (std::size_t k = 0; k < s.edges.size(); ++k)
    REQUIRE(s.edge_rest_m[k] ==
            Approx((s.rest_positions_m[s.edges[k].a] - s.rest_positions_m[s.edges[k].b]).norm()));
  // What crosses the cut is a ring around the body, a few per cent of the edges.
  const double across =
      static_cast<double>(s.edges.size() - s.edge_half_end[1]) / static_cast<double>(s.edges.size());
  std::vector<std::pair<uint32_t, uint32_t>> mesh_order;
  for (const ControlEdge& e : mesh.edges) mesh_order.push_back({e.a, e.b});
  WARN("1,000-point sedan: " << 100 * across << " % of the edges cross the cut; neighbours sharing a point: "
                             << 100 * sharedNeighbours(edges) << " % in the sweep, "
                             << 100 * sharedNeighbours(mesh_order) << " % in the mesh's order");
  CHECK(across < 0.05);
  // In the mesh's order most neighbours share a point (a chain of dependent updates); in the sweep's,
  // only where a window's colour changes.
  CHECK(sharedNeighbours(mesh_order) > 0.3);
  CHECK(sharedNeighbours(edges) < 0.15);
}

TEST_CASE("the sweep by level gives the windowed sweep's positions to the bit, in independent eights",
          "[dynamics]") {
  const ControlMesh mesh = sedanControlMesh(1000);
  std::vector<std::array<uint32_t, 2>> pairs;
  for (const ControlEdge& e : mesh.edges) pairs.push_back({e.a, e.b});
  const std::vector<uint8_t> halves = bodyHalves(mesh.points_m);
  const SweepOrder windowed = sweepOrder(pairs, halves, kSweepWindow, false);
  const SweepOrder levelled = sweepOrder(pairs, halves, kSweepWindow, true);
  CHECK(levelled.half_end == windowed.half_end);
  std::vector<uint32_t> sorted = levelled.order;
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t k = 0; k < sorted.size(); ++k) REQUIRE(sorted[k] == k);

  // Three Gauss-Seidel sweeps from the same shaken positions, one in each order.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> start = mesh.points_m;
  for (auto& p : start) p += 0.02 * Eigen::Vector3d(u(random), u(random), u(random));
  std::vector<double> w(start.size());
  for (double& wi : w) wi = 1 + 0.5 * u(random);
  auto sweep = [&](const SweepOrder& order) {
    std::vector<Eigen::Vector3d> x = start;
    std::vector<double> lambda(pairs.size(), 0.0);
    for (int pass = 0; pass < 3; ++pass)
      for (const uint32_t k : order.order) {
        const auto [a, b] = pairs[k];
        const double rest = (mesh.points_m[a] - mesh.points_m[b]).norm();
        projectDistance(x[a], x[b], w[a], w[b], rest, distanceFactors(w[a], w[b], 1e-7, 240.0 * 240.0),
                        lambda[k], -5e-4, 5e-4);
      }
    return x;
  };
  const std::vector<Eigen::Vector3d> by_window = sweep(windowed), by_level = sweep(levelled);
  CHECK(by_window != start);
  CHECK(by_level == by_window);

  // How many constraints the wide sweep takes eight at a time (disjointRuns) in each order.
  auto inEights = [&](const SweepOrder& order) {
    std::vector<uint32_t> interleaved;
    for (const uint32_t k : order.order) interleaved.insert(interleaved.end(), {pairs[k][0], pairs[k][1]});
    return shareInRuns(disjointRuns(interleaved), 8);
  };
  // And how many of them share a point with one of the eight before them (whose stores they wait for).
  auto waiting = [&](const SweepOrder& order) {
    std::size_t waits = 0;
    for (std::size_t j = 8; j < order.order.size(); ++j) {
      const auto [a, b] = pairs[order.order[j]];
      for (std::size_t back = j - 8; back < j - j % 8; ++back) {
        const auto [c, d] = pairs[order.order[back]];
        if (a == c || a == d || b == c || b == d) {
          ++waits;
          break;
        }
      }
    }
    return static_cast<double>(waits) / static_cast<double>(order.order.size());
  };
  WARN("1,000-point sedan's edges in eights: " << 100 * inEights(windowed) << " % by window, "
                                               << 100 * inEights(levelled) << " % by level; waiting on the "
                                               << "eight before: " << 100 * waiting(windowed) << " %, "
                                               << 100 * waiting(levelled) << " %");
  CHECK(inEights(levelled) > 0.9);
  CHECK(waiting(levelled) < 0.5 * waiting(windowed));
}

TEST_CASE("disjoint runs are the longest runs of constraints sharing no point", "[dynamics]") {
  // Random pairs among few points (short runs), among many (long runs, past the cap), and a constraint
  // joining a point to itself; against the count by every pair of the run.
  std::mt19937 random(11);
  for (const uint32_t points : {6u, 40u, 2000000u}) {
    std::uniform_int_distribution<uint32_t> pick(0, points - 1);
    std::vector<uint32_t> pairs;
    for (int k = 0; k < 600; ++k) {
      const uint32_t a = pick(random);
      pairs.insert(pairs.end(), {a, k == 300 ? a : pick(random)});
    }
    const std::size_t n = pairs.size() / 2;
    const std::vector<uint8_t> runs = disjointRuns(pairs);
    REQUIRE(runs.size() == n);
    std::size_t longest = 0;
    for (std::size_t k = 0; k < n; ++k) {
      std::size_t length = 0;
      std::set<uint32_t> used;
      while (k + length < n && length < kLongestRun) {
        const uint32_t a = pairs[2 * (k + length)], b = pairs[2 * (k + length) + 1];
        if (a == b || used.count(a) || used.count(b)) break;
        used.insert({a, b});
        ++length;
      }
      INFO(points << " points, constraint " << k);
      REQUIRE(runs[k] == length);
      longest = std::max(longest, length);
    }
    CHECK(runs[300] == 0);
    if (points == 2000000) CHECK(longest == kLongestRun);
  }
}

TEST_CASE("a 2000-point body's edges are mostly swept thirty-two at a time", "[dynamics]") {
  // The sweep's staged path (runs of 32 sharing no point) carries most of the edges of a fine body (about
  // 49 % at 500 points, 88 % at 1,000, 99 % at 4,000); the test above and `the wide sweep and prediction
  // give the one-by-one bits` check what it computes.
  const auto settings = makeSettings(sedanControlMesh(2000), 1500.0, BodyDescription{});
  std::vector<uint32_t> pairs;
  for (const EdgeConstraint& e : settings->edges) pairs.insert(pairs.end(), {e.a, e.b});
  const double share = shareInRuns(disjointRuns(pairs), 32);
  WARN("2,000-point sedan's edges in runs of 32: " << 100 * share << " %");
  CHECK(share > 0.9);
}

TEST_CASE("control points are numbered along the body's longest side", "[dynamics]") {
  const ControlMesh mesh = sedanControlMesh(500);
  for (std::size_t i = 1; i < mesh.points_m.size(); ++i)
    REQUIRE(mesh.points_m[i - 1].x() <= mesh.points_m[i].x());
  // The wings still lie on either side of each edge: the triangle a -> b -> left is one of the mesh's.
  std::set<std::array<uint32_t, 3>> triangles;
  for (auto t : mesh.triangles) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles.insert(t);
  }
  for (const ControlEdge& e : mesh.edges) {
    std::array<uint32_t, 3> t{e.a, e.b, e.left};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    REQUIRE(triangles.count(t) == 1);
  }
}

TEST_CASE("two threads sweep a body to the same bits as one", "[dynamics]") {
  for (const bool anchored : {true, false}) {
    BodyDescription d;
    d.anchored_columns = anchored;
    const auto settings = makeSettings(sedanControlMesh(500), 1500.0, d);
    SolverParams one;
    one.yield_limited = anchored;
    one.iterations = 2;
    SolverParams two = one;
    two.threads = 2;
    DeformableBody a(settings, one), b(settings, two);
    for (int k = 0; k < 90; ++k) {
      a.step(pressed(*settings, k), 1.0 / 60);
      b.step(pressed(*settings, k), 1.0 / 60);
    }
    INFO((anchored ? "anchored, force-limited" : "spokes, unlimited"));
    CHECK(a.state().plastic_work_J > 100);
    CHECK(hashState(a.state()) == hashState(b.state()));
  }
}

TEST_CASE("the wide sweep and prediction give the one-by-one bits", "[dynamics]") {
  if (!wideSweepAvailable()) {
    test_support::reportSkip("this machine has no AVX2: the wide sweep is not run");
    return;
  }
  // Force-limited crush columns (0, 2), unlimited spokes (1), unlimited columns (3) and force-limited
  // spokes (4); with the inertial forces (the chassis turning and braking) and without (2); an impulse
  // large enough for the prediction's travel cap now and then.
  for (const int variant : {0, 1, 2, 3, 4}) {
    BodyDescription d;
    d.anchored_columns = variant != 1 && variant != 4;
    const auto settings = makeSettings(sedanControlMesh(500), 1500.0, d);
    SolverParams narrow;
    narrow.yield_limited = variant == 0 || variant == 2 || variant == 4;
    narrow.inertial_scale = variant == 2 ? 0.0 : 1.0;
    narrow.wide_sweep = false;
    SolverParams wide = narrow;
    wide.wide_sweep = true;
    DeformableBody a(settings, narrow), b(settings, wide);
    for (int k = 0; k < 90; ++k) {
      StepInputs in = pressed(*settings, k);
      in.chassis.angular_velocity_radps = {0.1, -0.2, 0.5 + 0.01 * k};
      in.chassis.angular_acceleration_radps2 = {1.0, 0.5, -2.0};
      if (k % 30 == 5) in.impulses.push_back({7, Eigen::Vector3d(3000, -2000, 500)});
      const StepReport ra = a.step(in, 1.0 / 60), rb = b.step(in, 1.0 / 60);
      // The prediction's sums, lane by lane in point order.
      REQUIRE(ra.damping_loss_J == rb.damping_loss_J);
      REQUIRE(ra.inertial_work_J == rb.inertial_work_J);
      REQUIRE(ra.core_impulse_Ns == rb.core_impulse_Ns);
      // What the chassis takes (the shell orientation constraint's sum among it), and the obstacles' share.
      REQUIRE(ra.core_angular_impulse_Nms == rb.core_angular_impulse_Nms);
      REQUIRE(ra.contact_impulse_Ns == rb.contact_impulse_Ns);
      REQUIRE(ra.plastic_work_J == rb.plastic_work_J);
    }
    INFO("variant " << variant);
    // Force-limited edges yield (the clamp in the lanes), and the dent is deep enough to matter.
    CHECK(a.state().plastic_work_J > 100);
    CHECK(hashState(a.state()) == hashState(b.state()));
    CHECK(a.state().positions_m == b.state().positions_m);
    CHECK(a.state().plastic_work_J == b.state().plastic_work_J);
  }
}

TEST_CASE("the step factors give the textbook update to within rounding", "[dynamics]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Vector3d a(u(random), u(random), u(random)), b(u(random), u(random), u(random));
    const double wa = 1 + u(random), wb = 1 + u(random), compliance = 1e-6 * (1.5 + u(random));
    const double inv_h2 = 1.0 / (1.0 / 240 * 1.0 / 240), rest = (a - b).norm() * (1 + 0.2 * u(random));
    Eigen::Vector3d xa = a, xb = b, ya = a, yb = b;
    double lambda = 1e-6 * u(random), mu = lambda;
    referenceDistance(xa, xb, wa, wb, rest, compliance * inv_h2, lambda, -1e-4, 1e-4);
    projectDistance(ya, yb, wa, wb, rest, distanceFactors(wa, wb, compliance, inv_h2), mu, -1e-4, 1e-4);
    REQUIRE((xa - ya).norm() <= 1e-15 * (1 + a.norm()));
    REQUIRE((xb - yb).norm() <= 1e-15 * (1 + b.norm()));
    REQUIRE(std::abs(lambda - mu) <= 1e-14 * std::abs(lambda) + 1e-300);
  }
}

TEST_CASE("the visual constraint's near list gives the one-by-one bits, on one thread and on two",
          "[dynamics]") {
  // Tight caps (2 cm) that a post and a wall drive many points to; a light core, which each projection
  // at a cap moves by millimetres (past the list's 1 mm: the pass checks every point again), and a heavy
  // one, which it moves by less (the list alone).
  for (const double core_mass_kg : {15.0, 1500.0}) {
    INFO("core " << core_mass_kg << " kg");
    BodyDescription d;
    d.anchored_columns = true;
    d.max_deviation_m = 0.02;
    const auto settings = makeSettings(sedanControlMesh(500), 1500.0, d);
    SolverParams narrow;
    narrow.yield_limited = true;
    narrow.wide_sweep = false;
    SolverParams wide = narrow, wide_two = narrow;
    wide.wide_sweep = true;
    wide_two.wide_sweep = true;
    wide_two.threads = 2;
    DeformableBody a(settings, narrow), b(settings, wide), c(settings, wide_two);
    for (int k = 0; k < 60; ++k) {
      StepInputs in = pressed(*settings, k);
      in.core_mass_kg = core_mass_kg;
      const StepReport ra = a.step(in, 1.0 / 60), rb = b.step(in, 1.0 / 60), rc = c.step(in, 1.0 / 60);
      REQUIRE(ra.core_impulse_Ns == rb.core_impulse_Ns);
      REQUIRE(ra.core_impulse_Ns == rc.core_impulse_Ns);
      REQUIRE(ra.contact_impulse_Ns == rb.contact_impulse_Ns);
      REQUIRE(ra.contact_impulse_Ns == rc.contact_impulse_Ns);
    }
    // The caps held: some point sits at its cap, none beyond it.
    double farthest_m = 0;
    const auto& x = a.state().positions_m;
    for (std::size_t i = 0; i < x.size(); ++i)
      farthest_m = std::max(farthest_m, (x[i] - settings->rest_positions_m[i]).norm());
    CHECK(farthest_m > 0.019);
    CHECK(farthest_m < 0.0201);
    CHECK(a.state().positions_m == b.state().positions_m);
    CHECK(a.state().positions_m == c.state().positions_m);
    CHECK(hashState(a.state()) == hashState(c.state()));
  }
}
