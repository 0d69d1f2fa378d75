// A body moved onto a finer control surface (refinement.hpp): its points, masses and velocities by
// interpolation, its plastic rest shape from the coarse triangles' own rest metric.
#include <deform/error.hpp>
#include <deform/masses.hpp>
#include <deform/refinement.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace deform {
namespace {

uint64_t pairKey(uint32_t a, uint32_t b) {
  return a < b ? (static_cast<uint64_t>(a) << 32) | b : (static_cast<uint64_t>(b) << 32) | a;
}

uint64_t directedKey(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(a) << 32) | b;
}

Eigen::Vector2d leftNormal(const Eigen::Vector2d& u) {
  return {-u.y(), u.x()};
}

/// Where r lies when p and q are placed and the triangle (p, q, r) winds counter-clockwise, from its rest
/// lengths (law of cosines; a triangle its rest lengths cannot close is laid flat).
Eigen::Vector2d placeThird(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double pq_m, double pr_m,
                           double qr_m) {
  const double base_m = std::max(pq_m, 1e-12);
  const double along_m = (pr_m * pr_m - qr_m * qr_m + base_m * base_m) / (2.0 * base_m);
  const double height_m = std::sqrt(std::max(0.0, pr_m * pr_m - along_m * along_m));
  const Eigen::Vector2d u = (q - p).normalized();
  return p + along_m * u + height_m * leftNormal(u);
}

/// The body's coarse surface as it was: its edges' rest lengths now, and a flat layout of each coarse
/// leaf of the hierarchy by them.
class RestMetric {
 public:
  RestMetric(const SurfaceHierarchy& hierarchy, SurfaceHierarchy::Mark before, const BodySettings& settings,
             const BodyState& state)
      : hierarchy_(hierarchy), before_(before) {
    for (std::size_t e = 0; e < settings.edges.size(); ++e)
      edge_rest_.emplace(pairKey(settings.edges[e].a, settings.edges[e].b), state.edge_rest_m[e]);
  }

  /// Rest length of edge a-b of the coarse surface [m].
  double rest(uint32_t a, uint32_t b) const {
    const auto it = edge_rest_.find(pairKey(a, b));
    if (it == edge_rest_.end()) throw std::logic_error("refinement: a coarse edge the body does not have");
    return it->second;
  }
  bool hasEdge(uint32_t a, uint32_t b) const { return edge_rest_.count(pairKey(a, b)) != 0; }

  /// The coarse leaf node `fine` lies in: itself or its ancestor that was a leaf at `before`.
  uint32_t coarseLeaf(uint32_t fine) const {
    while (fine >= before_.nodes) fine = hierarchy_.nodes()[fine].parent;
    return fine;
  }

  /// Point `p` in the flat layout of coarse leaf `leaf`.
  Eigen::Vector2d at(uint32_t leaf, uint32_t p) {
    std::unordered_map<uint32_t, Eigen::Vector2d>& layout = layoutOf(leaf);
    const auto it = layout.find(p);
    if (it != layout.end()) return it->second;
    if (p < before_.points) throw std::logic_error("refinement: a coarse point outside its leaf");
    const auto [a, b] = hierarchy_.parentsOf(p);
    const Eigen::Vector2d place = 0.5 * (at(leaf, a) + at(leaf, b));
    layout.emplace(p, place);
    return place;
  }

 private:
  std::unordered_map<uint32_t, Eigen::Vector2d>& layoutOf(uint32_t leaf) {
    auto [it, fresh] = layouts_.try_emplace(leaf);
    if (!fresh) return it->second;
    const auto& c = hierarchy_.nodes()[leaf].corners;
    // A leaf was one coarse triangle, or two (green) on either side of the line from its split edge's
    // point to the opposite corner: laid out flat on that line.
    int split_edge = -1;
    uint32_t m = kNoIndex;
    for (int k = 0; k < 3; ++k) {
      const uint32_t mid =
          hierarchy_.midpoint(c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>((k + 1) % 3)]);
      if (mid != kNoIndex && mid < before_.points) {
        split_edge = k;
        m = mid;
      }
    }
    auto& layout = it->second;
    if (split_edge < 0) {
      const Eigen::Vector2d p(0, 0), q(rest(c[0], c[1]), 0);
      layout.emplace(c[0], p);
      layout.emplace(c[1], q);
      layout.emplace(c[2], placeThird(p, q, rest(c[0], c[1]), rest(c[0], c[2]), rest(c[1], c[2])));
      return layout;
    }
    const uint32_t x = c[static_cast<std::size_t>(split_edge)];
    const uint32_t y = c[static_cast<std::size_t>((split_edge + 1) % 3)];
    const uint32_t z = c[static_cast<std::size_t>((split_edge + 2) % 3)];
    const Eigen::Vector2d pm(0, 0), pz(rest(m, z), 0);
    layout.emplace(m, pm);
    layout.emplace(z, pz);
    layout.emplace(x,
                   placeThird(pm, pz, rest(m, z), rest(m, x), rest(z, x)));  // (m, z, x) winds as (x, m, z)
    layout.emplace(y,
                   placeThird(pz, pm, rest(m, z), rest(z, y), rest(m, y)));  // (z, m, y) winds as (m, y, z)
    return layout;
  }

  const SurfaceHierarchy& hierarchy_;
  SurfaceHierarchy::Mark before_;
  std::unordered_map<uint64_t, double> edge_rest_;
  std::unordered_map<uint32_t, std::unordered_map<uint32_t, Eigen::Vector2d>> layouts_;
};

/// Along the hinge a->b and away from it, where wing w lies in a flat layout [m].
struct WingPlace {
  double along_m = 0, away_m = 0;
};

WingPlace wingPlace(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& w) {
  const Eigen::Vector2d u = (b - a).normalized();
  const Eigen::Vector2d r = w - a;
  return {r.dot(u), std::abs(r.x() * u.y() - r.y() * u.x())};
}

/// Distance between two wings about a hinge at the turn whose cosine is cos_turn: the hinge's rest
/// fold is the angle the wings' perpendiculars make about it.
double wingDistance(const WingPlace& l, const WingPlace& r, double cos_turn) {
  const double ds = l.along_m - r.along_m;
  return std::sqrt(std::max(
      0.0, ds * ds + l.away_m * l.away_m + r.away_m * r.away_m - 2.0 * l.away_m * r.away_m * cos_turn));
}

/// `t` turned to start at its smallest corner (the same triangle, the same winding).
std::array<uint32_t, 3> canonical(const std::array<uint32_t, 3>& t) {
  const std::size_t k = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
  return {t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
}

/// Adds the spin that gives back `lost_Nms` of angular momentum to the points `moved` (their velocities
/// turned together about their centre of mass, so their momentum is unchanged).
void restoreSpin(const std::vector<uint32_t>& moved, const std::vector<double>& mass_kg,
                 const std::vector<Eigen::Vector3d>& x_m, std::vector<Eigen::Vector3d>& v_mps,
                 const Eigen::Vector3d& lost_Nms) {
  double mass = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (uint32_t i : moved) {
    mass += mass_kg[i];
    first += mass_kg[i] * x_m[i];
  }
  if (!(mass > 0)) return;
  const Eigen::Vector3d centre = first / mass;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (uint32_t i : moved) {
    const Eigen::Vector3d r = x_m[i] - centre;
    inertia += mass_kg[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  // The loss of each new point lies across its edge, where its edge's three points have inertia: a
  // pseudo-inverse turns about the axes that have it.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia);
  const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const double lambda = eigen.eigenvalues()[k];
    if (lambda > 1e-12 * largest)
      omega += eigen.eigenvectors().col(k) * (eigen.eigenvectors().col(k).dot(lost_Nms) / lambda);
  }
  for (uint32_t i : moved) v_mps[i] += omega.cross(x_m[i] - centre);
}

/// The hierarchy's surface as a control mesh around the core at `core_m`.
ControlMesh surfaceOf(const SurfaceHierarchy& hierarchy, const Eigen::Vector3d& core_m,
                      std::vector<uint32_t>* leaf_of) {
  ControlMesh mesh;
  mesh.points_m = hierarchy.restPoints();
  mesh.triangles = hierarchy.triangles(leaf_of);
  finishControlMesh(mesh);
  mesh.centre_of_mass_m = core_m;
  return mesh;
}

/// The constraints on the finer surface `mesh` with these point masses. A point a region lists by index is
/// joined by the points of its edges within the region; a point `coarse` has keeps its deviation cap, a new
/// one takes the tighter of its edge's. Every choice depends on the surface alone, not on the refinements
/// that made it.
BodySettings settingsOn(const SurfaceHierarchy& hierarchy, const ControlMesh& mesh,
                        const BodySettings& coarse, const BodyDescription& description,
                        const std::vector<double>& point_mass_kg) {
  const std::size_t n = mesh.points_m.size();
  BodyDescription finer = description;
  for (MaterialRegion& region : finer.regions) {
    if (region.points.empty()) continue;
    std::vector<char> member(n, 0);
    for (uint32_t p : region.points) member[p] = 1;
    for (std::size_t k = hierarchy.basePointCount(); k < n; ++k) {
      const auto [a, b] = hierarchy.parentsOf(static_cast<uint32_t>(k));
      if (member[a] && member[b] && !member[k]) {
        member[k] = 1;
        region.points.push_back(static_cast<uint32_t>(k));
      }
    }
  }
  MassSplit masses;
  masses.point_mass_kg = point_mass_kg;
  masses.core_mass_kg = coarse.core_mass_kg;
  BodySettings s = createBodySettings(mesh, masses, finer);
  for (std::size_t i = 0; i < coarse.pointCount(); ++i) s.max_deviation_m[i] = coarse.max_deviation_m[i];
  for (std::size_t k = coarse.pointCount(); k < n; ++k) {
    const auto [a, b] = hierarchy.parentsOf(static_cast<uint32_t>(k));
    s.max_deviation_m[k] = std::min(s.max_deviation_m[a], s.max_deviation_m[b]);
  }
  return s;
}

}  // namespace

TransferredBody transferBody(const SurfaceHierarchy& hierarchy, SurfaceHierarchy::Mark before,
                             const BodySettings& settings, const BodyState& state,
                             const BodyDescription& description) {
  const std::size_t old_n = before.points, n = hierarchy.restPoints().size();
  if (settings.pointCount() != old_n || state.positions_m.size() != old_n)
    throw std::logic_error("refinement: the body does not match the hierarchy's mark");

  std::vector<uint32_t> leaf_of;
  const ControlMesh mesh = surfaceOf(hierarchy, settings.core_m, &leaf_of);

  // The fan's shares, for the points' mass the body has (a car's points carry its shell, not 3/4 of it).
  std::vector<double> fan_kg = distributeMass(mesh, 1.0).point_mass_kg;
  {
    double fan_sum = 0, points_kg = 0;
    for (double m : fan_kg) fan_sum += m;
    for (double m : settings.mass_kg) points_kg += m;
    for (double& m : fan_kg) m *= points_kg / fan_sum;
  }
  std::vector<double> mass_kg = settings.mass_kg;
  mass_kg.resize(n, 0.0);
  BodyState out;
  out.positions_m = state.positions_m;
  out.velocities_mps = state.velocities_mps;
  out.column_rest_m = state.column_rest_m;
  out.positions_m.resize(n);
  out.velocities_mps.resize(n);
  out.column_rest_m.resize(n);
  // Each spoke's stretch past its rest length [m]: a new point's is the mean of its edge's, and each
  // spoke's rest length is its length on the finer surface less it. (Its rest place taken as the mean of
  // its edge's, as the anchored columns keep it, would not do for a spoke: two points turned about their
  // anchors have a midpoint that is not, and the 60-point sedan dented by a pole gained 102 J that way.)
  std::vector<double> spoke_stretch_m(n, 0.0);
  for (std::size_t i = 0; i < old_n; ++i)
    spoke_stretch_m[i] =
        (state.positions_m[i] - settings.core_m - settings.spoke_anchor_m[i]).norm() - state.spoke_rest_m[i];
  for (std::size_t k = old_n; k < n; ++k) {
    const auto [a, b] = hierarchy.parentsOf(static_cast<uint32_t>(k));
    out.positions_m[k] = 0.5 * (out.positions_m[a] + out.positions_m[b]);
    out.velocities_mps[k] = 0.5 * (out.velocities_mps[a] + out.velocities_mps[b]);
    out.column_rest_m[k] = 0.5 * (out.column_rest_m[a] + out.column_rest_m[b]);
    spoke_stretch_m[k] = 0.5 * (spoke_stretch_m[a] + spoke_stretch_m[b]);
  }

  // Masses: every point whose patch changed (the new ones, and the corners of the triangles that split)
  // takes what the tetrahedral fan gives it on the finer surface, tilted by the least linear field
  // m (1 + a + b . r) that keeps those points' mass and first moment, so the body's mass and centre of mass
  // stay. (A new point drawing its mass from its edge's ends kept them exactly too, but left the coarse
  // points heavy among light new ones: a ball thrown at the door refined to 1,160 points went 0.85 m in where
  // the same surface with the fan's masses stopped it at 0.64 m.)
  std::vector<char> moved(n, 0);
  for (std::size_t k = old_n; k < n; ++k) moved[k] = 1;
  {
    std::set<std::array<uint32_t, 3>> finer;
    for (const auto& t : mesh.triangles) finer.insert(canonical(t));
    for (const auto& t : settings.triangles)
      if (!finer.count(canonical(t)))
        for (uint32_t c : t) moved[c] = 1;
  }
  double old_kg = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < old_n; ++i)
    if (moved[i]) {
      old_kg += settings.mass_kg[i];
      centre += settings.mass_kg[i] * out.positions_m[i];
    }
  if (old_kg > 0) centre /= old_kg;
  // Normal equations of the tilt: [sum f, sum f r^T; sum f r, sum f r r^T] [a; b] = [M - sum f; F - sum f r].
  Eigen::Matrix4d lhs = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (!moved[i]) continue;
    Eigen::Vector4d row;
    row << 1.0, out.positions_m[i] - centre;
    lhs += fan_kg[i] * row * row.transpose();
    rhs -= fan_kg[i] * row;
    if (i < old_n) rhs += settings.mass_kg[i] * row;
  }
  const Eigen::Vector4d tilt = lhs.fullPivLu().solve(rhs);
  for (std::size_t i = 0; i < n; ++i) {
    if (!moved[i]) continue;
    const double scale = 1.0 + tilt[0] + tilt.tail<3>().dot(out.positions_m[i] - centre);
    mass_kg[i] = fan_kg[i] * scale;
    if (!(mass_kg[i] > 0))
      throw std::logic_error("refinement: the fan's masses could not keep the centre of mass");
  }
  // Momentum: the points whose mass changed move together by what they lost.
  Eigen::Vector3d lost_Ns = Eigen::Vector3d::Zero();
  double moved_kg = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!moved[i]) continue;
    if (i < old_n) lost_Ns += settings.mass_kg[i] * state.velocities_mps[i];
    lost_Ns -= mass_kg[i] * out.velocities_mps[i];
    moved_kg += mass_kg[i];
  }
  for (std::size_t i = 0; i < n; ++i)
    if (moved[i]) out.velocities_mps[i] += lost_Ns / moved_kg;

  const auto built =
      std::make_shared<const BodySettings>(settingsOn(hierarchy, mesh, settings, description, mass_kg));
  const BodySettings& s = *built;

  // Rest lengths: an edge the body had keeps its own; a new one is measured in the coarse triangle it lies
  // in, laid out flat by that triangle's rest lengths now.
  RestMetric metric(hierarchy, before, settings, state);
  // The coarse leaf each directed edge's triangle lies in; an edge lies in either of its two.
  std::unordered_map<uint64_t, uint32_t> leaf_of_directed;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      leaf_of_directed.emplace(directedKey(mesh.triangles[t][static_cast<std::size_t>(k)],
                                           mesh.triangles[t][static_cast<std::size_t>((k + 1) % 3)]),
                               metric.coarseLeaf(leaf_of[t]));
  out.edge_rest_m.resize(s.edges.size());
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const uint32_t a = s.edges[e].a, b = s.edges[e].b;
    if (metric.hasEdge(a, b)) {
      out.edge_rest_m[e] = metric.rest(a, b);
      continue;
    }
    const uint32_t leaf = leaf_of_directed.at(directedKey(a, b));
    out.edge_rest_m[e] = (metric.at(leaf, a) - metric.at(leaf, b)).norm();
  }
  out.spoke_rest_m.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    out.spoke_rest_m[i] = (out.positions_m[i] - s.core_m - s.spoke_anchor_m[i]).norm() - spoke_stretch_m[i];

  // Bends: one the body had keeps its rest length; a new one, across part of a coarse hinge, the fold that
  // hinge has now (its wings' turn about it, from its rest lengths), on the wings' flat layouts.
  std::unordered_map<uint64_t, uint32_t> coarse_bend;  // each piece of a coarse hinge -> that hinge's bend
  for (std::size_t j = 0; j < settings.bends.size(); ++j) {
    std::vector<std::array<uint32_t, 2>> pieces = {{settings.bends[j].hinge_a, settings.bends[j].hinge_b}};
    while (!pieces.empty()) {
      const auto [p, q] = pieces.back();
      pieces.pop_back();
      const uint32_t mid = hierarchy.midpoint(p, q);
      if (mid == kNoIndex) {
        coarse_bend.emplace(pairKey(p, q), static_cast<uint32_t>(j));
      } else {
        pieces.push_back({p, mid});
        pieces.push_back({mid, q});
      }
    }
  }
  // The cosine of coarse bend j's turn, from its rest lengths (the plastic fold it has now).
  auto coarseTurn = [&](uint32_t j) {
    const BendConstraint& c = settings.bends[j];
    const double pq = metric.rest(c.hinge_a, c.hinge_b);
    const Eigen::Vector2d p(0, 0), q(pq, 0);
    const Eigen::Vector2d l =
        placeThird(p, q, pq, metric.rest(c.hinge_a, c.left), metric.rest(c.hinge_b, c.left));
    const Eigen::Vector2d r =
        placeThird(p, q, pq, metric.rest(c.hinge_a, c.right), metric.rest(c.hinge_b, c.right));
    const WingPlace wl = wingPlace(p, q, l), wr = wingPlace(p, q, r);
    const double d = state.bend_rest_m[j];
    const double ds = wl.along_m - wr.along_m;
    const double denominator = 2.0 * wl.away_m * wr.away_m;
    if (!(denominator > 0)) return -1.0;
    return std::clamp((ds * ds + wl.away_m * wl.away_m + wr.away_m * wr.away_m - d * d) / denominator, -1.0,
                      1.0);
  };
  std::map<std::array<uint64_t, 2>, uint32_t> old_bend;  // (wings, hinge) -> the body's bend
  for (std::size_t j = 0; j < settings.bends.size(); ++j) {
    const BendConstraint& c = settings.bends[j];
    old_bend.emplace(std::array<uint64_t, 2>{pairKey(c.left, c.right), pairKey(c.hinge_a, c.hinge_b)},
                     static_cast<uint32_t>(j));
  }
  out.bend_rest_m = s.bend_rest_m;
  for (std::size_t j = 0; j < s.bends.size(); ++j) {
    const BendConstraint& c = s.bends[j];
    const auto same = old_bend.find({pairKey(c.left, c.right), pairKey(c.hinge_a, c.hinge_b)});
    if (same != old_bend.end()) {
      out.bend_rest_m[j] = state.bend_rest_m[same->second];
      continue;
    }
    const auto coarse = coarse_bend.find(pairKey(c.hinge_a, c.hinge_b));
    if (coarse == coarse_bend.end()) continue;  // a hinge the coarse body did not bend across: as built
    // The wings' triangles, (a, b, left) and (b, a, right), each in its coarse leaf's layout.
    const uint32_t left_leaf = leaf_of_directed.at(directedKey(c.hinge_a, c.hinge_b));
    const uint32_t right_leaf = leaf_of_directed.at(directedKey(c.hinge_b, c.hinge_a));
    const WingPlace wl = wingPlace(metric.at(left_leaf, c.hinge_a), metric.at(left_leaf, c.hinge_b),
                                   metric.at(left_leaf, c.left));
    const WingPlace wr = wingPlace(metric.at(right_leaf, c.hinge_a), metric.at(right_leaf, c.hinge_b),
                                   metric.at(right_leaf, c.right));
    out.bend_rest_m[j] = wingDistance(wl, wr, coarseTurn(coarse->second));
  }

  // Angular momentum: the averaged velocities lost sum (m/4) (x_a - x_b) x (v_a - v_b) over the new points;
  // the new points and their edges' ends turn together to give it back.
  Eigen::Vector3d before_Nms = Eigen::Vector3d::Zero(), after_Nms = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < old_n; ++i)
    before_Nms +=
        settings.mass_kg[i] * (state.positions_m[i] - settings.core_m).cross(state.velocities_mps[i]);
  for (std::size_t i = 0; i < n; ++i)
    after_Nms += s.mass_kg[i] * (out.positions_m[i] - settings.core_m).cross(out.velocities_mps[i]);
  std::vector<uint32_t> moved_points;
  for (std::size_t i = 0; i < n; ++i)
    if (moved[i]) moved_points.push_back(static_cast<uint32_t>(i));
  restoreSpin(moved_points, s.mass_kg, out.positions_m, out.velocities_mps, before_Nms - after_Nms);

  out.plastic_work_J = state.plastic_work_J;
  out.time_s = state.time_s;
  out.sleep_timer_s = 0;
  out.sleeping = false;
  return {built, std::move(out)};
}

std::shared_ptr<const BodySettings> refinedSettings(const SurfaceHierarchy& hierarchy,
                                                    const BodySettings& start,
                                                    const BodyDescription& description,
                                                    const std::vector<double>& point_mass_kg) {
  if (start.pointCount() != hierarchy.basePointCount())
    throw InputError("refinement: a start body of " + std::to_string(start.pointCount()) +
                     " control points for a hierarchy over " + std::to_string(hierarchy.basePointCount()));
  if (point_mass_kg.size() != hierarchy.restPoints().size())
    throw InputError("refinement: " + std::to_string(point_mass_kg.size()) + " point masses for " +
                     std::to_string(hierarchy.restPoints().size()) + " control points");
  return std::make_shared<const BodySettings>(
      settingsOn(hierarchy, surfaceOf(hierarchy, start.core_m, nullptr), start, description, point_mass_kg));
}

}  // namespace deform
