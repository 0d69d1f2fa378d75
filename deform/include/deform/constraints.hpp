#pragma once
// The constraint kinds of the deformable body, each a plain struct kept in its own array and solved by
// its own loop, and the pure functions that project them (testable alone). XPBD: Macklin, Mueller,
// Chentanez 2016, "XPBD: Position-Based Simulation of Compliant Constrained Dynamics":
//   alpha~ = alpha / h^2                                  (the time-step scaled compliance)
//   d_lambda = (-C - alpha~ lambda) / (grad C M^-1 grad C^T + alpha~)   (eq. 18)
//   d_x = M^-1 grad C^T d_lambda                          (eq. 17)
// with lambda reset to zero at the start of every substep (Macklin et al. 2019, "Small Steps").
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace deform {

/// A hull edge between control points `a` and `b` (the shell's structure).
struct EdgeConstraint {
  uint32_t a = 0, b = 0;          ///< control points
  uint32_t material = 0;          ///< index into BodySettings::materials
  double compliance_m_per_N = 0;  ///< from the material [m/N]
};

/// A spoke from control point `point` to the rigid core (kinematic: it moves with the chassis).
struct SpokeConstraint {
  uint32_t point = 0;             ///< control point
  uint32_t material = 0;          ///< index into BodySettings::materials
  double compliance_m_per_N = 0;  ///< from the material [m/N]
};

/// Bending across the hull edge `hinge_a`-`hinge_b`: a distance constraint between the two wing
/// vertices `left` and `right` (the "distance" bend of Jolt's soft bodies; Kenwright 2015 "Dynamics":
/// a point-based bending term).
/// On a convex hull the hinge is never flat at rest except on refined faces, where the spokes carry the
/// out-of-plane load.
struct BendConstraint {
  uint32_t left = 0, right = 0;       ///< wing vertices, the constrained pair
  uint32_t hinge_a = 0, hinge_b = 0;  ///< the shared edge (for reference and regions)
  uint32_t material = 0;              ///< index into BodySettings::materials
  double compliance_m_per_N = 0;      ///< from the material [m/N]
};

/// Below this length [m] a distance constraint has no direction and is skipped (numeric guard).
inline constexpr double kMinConstraintLength_m = 1e-12;

/// What a distance constraint's XPBD update takes from the step alone: alpha_tilde = compliance / h^2
/// [1/kg] and 1 / (w_a + w_b + alpha_tilde) [kg] (0 where that sum is not positive: no update). Found
/// once per substep length, it spares the sweep a division per constraint.
struct DistanceFactors {
  double alpha_tilde = 0;
  double inverse_denominator = 0;
};
inline DistanceFactors distanceFactors(double wa, double wb, double compliance_m_per_N, double inv_h2) {
  DistanceFactors f;
  f.alpha_tilde = compliance_m_per_N * inv_h2;
  const double denominator = wa + wb + f.alpha_tilde;
  f.inverse_denominator = denominator > 0 ? 1.0 / denominator : 0.0;
  return f;
}

/// XPBD distance constraint C = |x_a - x_b| - rest (eq. 17, 18), Gauss-Seidel: moves `xa` and `xb`
/// by their inverse masses [1/kg] and accumulates the multiplier `lambda` [N s^2], with the step's
/// factors found beforehand (distanceFactors): the multiplier's step (-C - alpha~ lambda) / (w_a + w_b +
/// alpha~) is a product, not a quotient. `xb` may be the core's place (a spoke: w_b the core's inverse
/// mass, 0 = kinematic). Returns C before the projection [m].
/// A yielding constraint carries no more than its yield force: `lambda` stays within [lambda_min,
/// lambda_max] (tension is negative: -F_stretch h^2 .. F_shorten h^2), and what the clamp leaves of C is
/// plastic flow for the substep's return map (a force-limited constraint, like a motor's maximum impulse).
[[gnu::always_inline]] inline double projectDistance(Eigen::Vector3d& xa, Eigen::Vector3d& xb, double wa,
                                                     double wb, double rest_m, const DistanceFactors& factors,
                                                     double& lambda, double lambda_min = -HUGE_VAL,
                                                     double lambda_max = HUGE_VAL) {
  const Eigen::Vector3d d = xa - xb;
  const double length = d.norm();
  if (length < kMinConstraintLength_m) return 0;
  const double c = length - rest_m;
  double next = lambda + (-c - factors.alpha_tilde * lambda) * factors.inverse_denominator;
  // Unbounded (the default) folds away when inlined with constant bounds: the plain XPBD update.
  if (lambda_min != -HUGE_VAL || lambda_max != HUGE_VAL) next = std::clamp(next, lambda_min, lambda_max);
  const double d_lambda = next - lambda;
  lambda = next;
  const Eigen::Vector3d n = d * (d_lambda / length);  // grad_xa C * d_lambda
  xa += wa * n;
  xb -= wb * n;
  return c;
}

/// A crush column held at its rest place: the zero-length XPBD constraint C = x - target (three rows of
/// one isotropic compliance, eq. 17, 18) between a control point `x` (inverse mass `w` [1/kg]) and the
/// place `target` [m] where the column holds it now, which moves with the core (inverse mass `w_core`;
/// 0 = kinematic). The multiplier `lambda` [N s^2] is a vector; when `lambda_limit` is given it is the
/// largest |lambda| the column carries in the direction it pushes (a force-limited column); `surely_within`,
/// when given, says without a square root that a multiplier is certainly within that limit (it must
/// never say so of one beyond it), which spares the limit's evaluation. Returns |C| before the
/// projection [m].
template <typename Limit, typename Within = std::nullptr_t>
[[gnu::always_inline]] inline void projectColumn(Eigen::Vector3d& x, const Eigen::Vector3d& target, double w,
                                                 const DistanceFactors& factors, Eigen::Vector3d& lambda,
                                                 Limit&& lambda_limit, Within&& surely_within = nullptr) {
  const Eigen::Vector3d c = x - target;
  Eigen::Vector3d next = lambda + (-c - factors.alpha_tilde * lambda) * factors.inverse_denominator;
  if constexpr (!std::is_same_v<std::decay_t<Limit>, std::nullptr_t>) {
    bool within = false;
    if constexpr (!std::is_same_v<std::decay_t<Within>, std::nullptr_t>) within = surely_within(next);
    const double magnitude = within ? 0.0 : next.norm();
    if (magnitude > 0) {
      const double limit = lambda_limit(next / magnitude);
      if (magnitude > limit) next *= limit / magnitude;
    }
  }
  x += w * (next - lambda);
  lambda = next;
}

/// The same with the step's factors found here (distanceFactors(w, w_core, compliance, 1 / h^2) gives
/// them once per substep length, as the sweep does). Returns |C| before the projection [m].
template <typename Limit, typename Within = std::nullptr_t>
inline double projectColumn(Eigen::Vector3d& x, const Eigen::Vector3d& target, double w, double w_core,
                            double alpha_tilde, Eigen::Vector3d& lambda, Limit&& lambda_limit,
                            Within&& surely_within = nullptr) {
  const double sum = w + w_core;
  if (sum + alpha_tilde <= 0) return 0;
  const double violation = (x - target).norm();
  projectColumn(x, target, w, DistanceFactors{alpha_tilde, 1.0 / (sum + alpha_tilde)}, lambda,
                std::forward<Limit>(lambda_limit), std::forward<Within>(surely_within));
  return violation;
}

/// Non-penetration of a point with an immovable obstacle, linearised as the half-space
/// n . (x - surface) >= 0 for the substep (Mueller et al. 2007, "Position Based Dynamics": collision
/// constraints generated once per step, solved with the others), with Coulomb friction at position
/// level (Macklin et al. 2014, "Unified Particle Physics", eq. 24): the tangential travel relative to the
/// obstacle's surface, `x_start` to `x` (`x_start`: where the point began the substep, carried along with
/// the surface), is cancelled while within friction x the depth corrected, else shortened by that much. Moves
/// `x` onto the surface when inside; returns the depth corrected [m].
inline double projectContact(Eigen::Vector3d& x, const Eigen::Vector3d& x_start,
                             const Eigen::Vector3d& normal, const Eigen::Vector3d& surface_m,
                             double friction) {
  const double c = normal.dot(x - surface_m);
  if (c >= 0) return 0;
  x -= c * normal;
  if (friction > 0) {
    const Eigen::Vector3d travel = x - x_start;
    const Eigen::Vector3d tangential = travel - normal.dot(travel) * normal;
    const double length = tangential.norm(), limit = -friction * c;
    x -= length <= limit ? tangential : Eigen::Vector3d(tangential * (limit / length));
  }
  return -c;
}

/// Face contact: a point of the control surface between control points, p = sum bary_k x_k, found
/// inside an obstacle, must come out to the plane through `surface_m` with unit `normal` (out of the
/// obstacle): C = normal . (p - surface) >= 0. Projected as PBD over the corners weighted by inverse
/// mass (Mueller et al. 2007, eq. 8 with grad_k C = bary_k normal), which moves p exactly onto the plane.
/// A movable obstacle of inverse mass `w_obstacle` > 0 (grad C = -normal for it) shares the correction:
/// its displacement is added to `obstacle_move`. Returns the depth corrected [m].
inline double projectFaceContact(Eigen::Vector3d& x0, Eigen::Vector3d& x1, Eigen::Vector3d& x2,
                                 const double w[3], const Eigen::Vector3d& bary,
                                 const Eigen::Vector3d& normal, const Eigen::Vector3d& surface_m,
                                 double w_obstacle = 0, Eigen::Vector3d* obstacle_move = nullptr) {
  const double c = normal.dot(bary[0] * x0 + bary[1] * x1 + bary[2] * x2 - surface_m);
  if (c >= 0) return 0;
  const double denominator =
      w[0] * bary[0] * bary[0] + w[1] * bary[1] * bary[1] + w[2] * bary[2] * bary[2] + w_obstacle;
  if (!(denominator > 0)) return 0;
  const double scale = -c / denominator;
  x0 += (scale * w[0] * bary[0]) * normal;
  x1 += (scale * w[1] * bary[1]) * normal;
  x2 += (scale * w[2] * bary[2]) * normal;
  if (obstacle_move) *obstacle_move -= (scale * w_obstacle) * normal;
  return -c;
}

/// Visual constraint (Kenwright 2015, "Visual Constraints"): |x - x0| <= max_deviation. Projects `x`
/// onto the ball around its starting position `x0`; returns true when it moved it.
inline bool projectVisual(Eigen::Vector3d& x, const Eigen::Vector3d& x0, double max_deviation_m) {
  const Eigen::Vector3d d = x - x0;
  const double squared = d.squaredNorm();
  if (squared <= max_deviation_m * max_deviation_m) return false;
  x = x0 + d * (max_deviation_m / std::sqrt(squared));
  return true;
}

/// Shell orientation: the closed triangulated shell is rigid as a framework (Cauchy), and spokes fix
/// its translation, but nothing in edges, bends or spokes resists a rotation of the whole shell about
/// the core: three zero-stiffness modes, which contacts sliding tangentially would excite. A real body is
/// bolted to its chassis, so this global constraint ties the shell's mean rotation to the chassis:
///   G(x) = sum_i m_i r_i x (x_i - x0_i) = 0,  r_i = x0_i - core
/// (linear in x, so one PBD projection, d_x_i = mu x r_i with A mu = -G, A = sum_i m_i (|r_i|^2 I - r_i
/// r_i^T) the shell's inertia about the core, meets it exactly). A dent, being radial, has no rotation
/// and is left alone. `shift_m` is how far the core (and the rest shape with it) has moved from `core_m`.
/// The core's reaction is minus the angular momentum (x h) the projection gave the points about the core,
/// -sum_i m_i (x_i - core) x d_x_i [kg m^2]. That is -A mu = G
/// only while x = x0; a crushed shell (front 0.75 m in) moved by mu x r_i at levers x_i - core takes a
/// different moment, and reporting G made the body a torque on itself (repeated_impacts: ~6 kN m of yaw
/// while driving straight, 22 kJ created). In two functions, so that the shell can be taken in parts
/// (SolverParams::threads): shellRotation sums G, turnShell moves the points by mu = -A^-1 G, adds
/// sum_i m_i d_x_i to `push` [kg m] and returns sum_i m_i (x_i - core) x d_x_i.
///
/// G over the points [0, n) of the arrays given (the whole shell's is the sum over its parts) ...
inline Eigen::Vector3d shellRotation(const Eigen::Vector3d* x, const Eigen::Vector3d* x0,
                                     const double* mass_kg, std::size_t n, const Eigen::Vector3d& core_m,
                                     const Eigen::Vector3d& shift_m) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) g += mass_kg[i] * (x0[i] - core_m).cross(x[i] - shift_m - x0[i]);
  return g;
}

/// ... and the projection d_x_i = mu x r_i of those points, with mu = -A^-1 G of the whole shell: adds
/// their share of sum_i m_i d_x_i to `push` and returns their share of the angular momentum given.
inline Eigen::Vector3d turnShell(Eigen::Vector3d* x, const Eigen::Vector3d* x0, const double* mass_kg,
                                 std::size_t n, const Eigen::Vector3d& core_m, const Eigen::Vector3d& shift_m,
                                 const Eigen::Vector3d& mu, Eigen::Vector3d& push) {
  Eigen::Vector3d given{0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d dx = mu.cross(x0[i] - core_m);
    given += mass_kg[i] * (x[i] - shift_m - core_m).cross(dx);
    x[i] += dx;
    push += mass_kg[i] * dx;
  }
  return given;
}

/// How far one constraint may be stretched or shortened elastically before its rest length flows [m]:
/// its yield force times its compliance, fixed by the original geometry (body_settings.cpp).
struct YieldLimits {
  double stretch_m = 0;  ///< elastic elongation l - L at yield in tension [m], >= 0
  double shorten_m = 0;  ///< elastic shortening L - l at yield in compression [m], >= 0
};

/// Plasticity of one constraint: the material constants it needs besides its yield limits.
struct PlasticLaw {
  double hardening = 0;          ///< plastic / elastic modulus ratio [1]
  double min_rest_fraction = 0;  ///< lower clamp of L / L0 [1]
  double max_rest_fraction = 0;  ///< upper clamp of L / L0 [1]
};

/// The force a constraint carries at yield now [N]: its yield elongation (raised by hardening as it has
/// flowed) over its compliance; infinite for a rigid one (alpha = 0), which has no yield force.
struct YieldForce {
  float stretch_N = HUGE_VALF, shorten_N = HUGE_VALF;
};
inline YieldForce yieldForce(double compliance_m_per_N, double rest_m, double original_rest_m,
                             const YieldLimits& yield, const PlasticLaw& law) {
  YieldForce out;
  if (!(compliance_m_per_N > 0)) return out;
  const double taken = law.hardening * std::abs(rest_m - original_rest_m);
  // At its rest-length clamp a constraint can flow no further that way: it bottoms out, rigidly elastic.
  if (rest_m < law.max_rest_fraction * original_rest_m)
    out.stretch_N = static_cast<float>((yield.stretch_m + taken) / compliance_m_per_N);
  if (rest_m > law.min_rest_fraction * original_rest_m)
    out.shorten_N = static_cast<float>((yield.shorten_m + taken) / compliance_m_per_N);
  return out;
}

/// Return map of the rest length (1D elastoplasticity with linear hardening, Simo and Hughes 1998,
/// Box 1.1, in elongations): with the elastic elongation e = l - L and the yield elongation grown by
/// hardening, e_y = yield + H |L - L0|, an elongation past e_y moves L towards l by (|e| - e_y) / (1 + H);
/// the result is clamped to [min, max] x L0. Returns the new rest length [m]; `length_m` is the current
/// length l, `rest_m` is L and `original_rest_m` is L0.
inline double plasticRestLength(double length_m, double rest_m, double original_rest_m,
                                const YieldLimits& yield, const PlasticLaw& law) {
  if (!(rest_m > 0) || !(original_rest_m > 0)) return rest_m;
  const double elongation = length_m - rest_m;
  const double taken = law.hardening * std::abs(rest_m - original_rest_m);
  const double limit = (elongation > 0 ? yield.stretch_m : yield.shorten_m) + taken;
  const double magnitude = std::abs(elongation);
  if (!(magnitude > limit)) return rest_m;
  const double flow = (magnitude - limit) / (1.0 + law.hardening);
  const double moved = elongation > 0 ? rest_m + flow : rest_m - flow;
  return std::clamp(moved, law.min_rest_fraction * original_rest_m, law.max_rest_fraction * original_rest_m);
}

/// Relative margin of the square-root-free "surely" tests below (elastic bands, columns): a value this
/// close to a bound goes to the exact test, so rounding can never make a shortcut skip a flow or a clamp.
inline constexpr double kSurelyMargin = 1e-9;

/// The squared lengths [m^2] strictly between which plasticRestLength leaves a rest length alone, with a
/// relative margin of kSurelyMargin inside the exact bounds (rest - shorten - taken, rest + stretch + taken)
/// so that rounding can never make it skip a flow. Plasticity visits every constraint every substep and
/// nearly all of them are elastic: with the band cached per constraint, those cost a squared length and two
/// comparisons, not a square root and a return map. A constraint whose rest length flows gets a new band.
struct ElasticBand {
  double shortest_m2 = -1;       ///< below (or at) this squared length it may flow in compression
  double longest_m2 = HUGE_VAL;  ///< above (or at) this squared length it may flow in tension
  bool holds(double length_m2) const { return length_m2 > shortest_m2 && length_m2 < longest_m2; }
};
inline ElasticBand elasticBand(double rest_m, double original_rest_m, const YieldLimits& yield,
                               const PlasticLaw& law) {
  ElasticBand band;
  if (!(rest_m > 0) || !(original_rest_m > 0)) return band;  // plasticRestLength never moves it
  const double taken = law.hardening * std::abs(rest_m - original_rest_m);
  const double longest = rest_m + yield.stretch_m + taken;
  const double shortest = rest_m - (yield.shorten_m + taken);
  band.longest_m2 = longest * longest * (1 - kSurelyMargin);
  band.shortest_m2 = shortest > 0 ? shortest * shortest * (1 + kSurelyMargin) : -1;
  return band;
}

/// Elastic displacement [m] after which a crush column yields when its point is displaced along the unit
/// `direction` from its rest place: the column resists a motion by the volume its patch of skin sweeps,
/// |a . d| per metre of travel (a = |a| n its vector area, n outward), so pressed in (n . d < 0) it
/// yields after shorten_m |n . d| and pulled out after stretch_m |n . d|, plus what hardening has added
/// (`taken_m`). A flat obstacle pushing a slanted patch meets the crush strength on the patch's area as
/// seen along the push, whatever the slope: the summed resistance of a front is its cross-section's.
inline double columnYield_m(const Eigen::Vector3d& normal, const Eigen::Vector3d& direction,
                            const YieldLimits& yield, double taken_m) {
  const double along = normal.dot(direction);
  return (along < 0 ? yield.shorten_m : yield.stretch_m) * std::abs(along) + taken_m;
}

/// True when a crush column displaced by `elastic` (x - rest) [m] is certainly within its yield, found
/// without a square root: |e|^2 (1 + margin) <= s |n . e|, with s its yield along the normal alone, which
/// is at most what plasticColumnRest allows (|e| <= s |n . e| / |e| + taken, taken >= 0). False does not
/// mean it flows: plasticColumnRest decides.
inline bool columnSurelyElastic(const Eigen::Vector3d& normal, const Eigen::Vector3d& elastic,
                                const YieldLimits& yield) {
  const double along = normal.dot(elastic);
  return elastic.squaredNorm() * (1 + kSurelyMargin) <=
         (along < 0 ? yield.shorten_m : yield.stretch_m) * std::abs(along);
}

/// True when a force-limited crush column's multiplier `next` [N s^2] is certainly within the limit its
/// sweep puts on it (to_lambda x columnYield_m along its push, infinite once bottomed out and pushing in),
/// found without a square root: |next|^2 (1 + margin) <= to_lambda s |n . next|, the yield along the normal
/// alone (taken >= 0 only adds). False does not mean it is beyond: the limit decides.
inline bool columnSurelyWithinLimit(const Eigen::Vector3d& normal, const Eigen::Vector3d& next,
                                    const YieldLimits& yield, double to_lambda, bool bottomed) {
  const double along = normal.dot(next);  // > 0: the column pushes its point in (it is shortened)
  if (bottomed && along > 0) return true;
  const double yield_m = along > 0 ? yield.shorten_m : yield.stretch_m;
  return next.squaredNorm() * (1 + kSurelyMargin) <= to_lambda * yield_m * std::abs(along);
}

/// Return map of a crush column's rest place (the 1D return map of plasticRestLength along the
/// elastic displacement e = x - rest, with the direction-dependent yield of columnYield_m): a point
/// displaced past its yield drags its rest place along e by (|e| - e_y) / (1 + H). The crush depth
/// along the normal, n . (original - rest), stays within [(1 - max_rest_fraction), (1 - min_rest_fraction)]
/// x `length0_m` (the column's original length). All positions in one frame [m]; returns the new rest.
inline Eigen::Vector3d plasticColumnRest(const Eigen::Vector3d& x, const Eigen::Vector3d& rest,
                                         const Eigen::Vector3d& original, const Eigen::Vector3d& normal,
                                         double length0_m, const YieldLimits& yield, const PlasticLaw& law) {
  const Eigen::Vector3d elastic = x - rest;
  const double magnitude = elastic.norm();
  if (!(magnitude > 0)) return rest;
  const Eigen::Vector3d direction = elastic / magnitude;
  const double taken = law.hardening * (rest - original).norm();
  const double limit = columnYield_m(normal, direction, yield, taken);
  if (!(magnitude > limit)) return rest;
  Eigen::Vector3d moved = rest + direction * ((magnitude - limit) / (1.0 + law.hardening));
  const double depth = normal.dot(original - moved);
  const double kept =
      std::clamp(depth, (1.0 - law.max_rest_fraction) * length0_m, (1.0 - law.min_rest_fraction) * length0_m);
  moved += (depth - kept) * normal;
  return moved;
}

}  // namespace deform
