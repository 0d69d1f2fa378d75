#pragma once
// The per-car knobs of the deformation solver: the speed/accuracy trade (substeps, iterations) and the
// few physical parameters that are not the material's (damping, secondary motion, sleep).
#include <cmath>
#include <cstdint>

namespace deform {

/// The solver's knobs per body (DeformableBody's constructor, setParams).
struct SolverParams {
  /// Substeps per step (Macklin et al. 2019, "Small Steps"): each does prediction, `iterations`
  /// Gauss-Seidel sweeps, the visual constraint, plasticity and the velocity update. >= 1.
  uint32_t substeps = 4;
  /// Gauss-Seidel sweeps over every constraint per substep. >= 1.
  uint32_t iterations = 1;
  /// Threads that step this body: 1, or 2 for its two halves side by side (OpenMP; more are taken as
  /// 2): the sweep (BodySettings::edge_half_end), the prediction, the contact search, plasticity,
  /// the shell's orientation, the visual constraint's search for points near their caps and the velocities.
  /// The state is bit-identical for 1 and 2: each half visits the same items in the same order and keeps its
  /// own sums, added half 0 first. Inside a parallel region (bodies stepped side by side) the body runs on
  /// its caller's thread. Worth it only with cores to spare: OpenMP's threads wait by spinning, and two
  /// processes each sweeping on two threads of a 2-core machine ran 10-100x slower (the scenes keep 1 and
  /// spread their cars over the threads instead). >= 1.
  uint32_t threads = 1;
  /// Four at a time where the machine has AVX2: the edges (or bends) where four (or eight) neighbours in
  /// the sweep share no point, the crush columns and spokes, the prediction, the shell orientation
  /// constraint and plasticity's tests; and the visual constraint projects only the points near their
  /// caps (listed by the halves), not every point. The state and the step's sums are the same to the bit
  /// either way (each lane does the one-at-a-time operations in their order; a point left out is surely
  /// inside its cap): the knob is there to measure the gain (`bench step --narrow`) and to test that
  /// sameness.
  bool wide_sweep = true;
  /// Viscous drag on the control points' motion relative to the chassis, per unit mass [1/s]: with no
  /// constraint acting, a speed decays as exp(-damping_per_s t) (applied exactly per substep, so it is
  /// stable for any value). 0 = undamped. >= 0.
  double damping_per_s = 2.0;
  /// Scale of the inertial (fictitious) forces from the chassis's motion and of gravity (the paper's
  /// secondary motion) [1]; 0 disables them. >= 0.
  double inertial_scale = 1.0;
  /// Points closer than this to an obstacle [m] get a contact constraint for the substep (inactive until
  /// violated), so a point resting on a surface stays there instead of jittering in and out. >= 0.
  double contact_margin_m = 0.01;
  /// A point (or a point of a face) that begins a substep inside an obstacle is pushed out of that depth
  /// at most this fast [m/s]; motion further in is still stopped in full. Without it, an obstacle placed
  /// deep in the body (a teleport, a body started inside) throws the points out at depth / h, however small
  /// the substep h (0.2 m at h = 1.6e-7 s: 1e6 m/s). The cap on resolving overlap of Box2D v3
  /// (`contactPushMaxVelocity`, 3 m/s) and PhysX (`maxDepenetrationVelocity`). Infinite: no cap. > 0.
  double max_depenetration_mps = 10.0;
  /// A step with something in contact (an obstacle, or another body stepped as one with it: stepGroup)
  /// takes substeps no longer than this [s], more than `substeps` where the step needs it. Infinite (the
  /// default): `substeps` alone. > 0. Fine bodies in contact at long substeps were not held by the
  /// iterations: a pile of four 1,000-point cars at 120 Hz, 4 substeps of 2.1 ms, left 21 times the
  /// runner's kinetic energy unexplained, 8 % at 0.5 ms; a 250-point car against a tree -17 %, +0.8 % at
  /// 0.5 ms (docs/CRASH_CALIBRATION.md, "Two cars, one solve").
  double longest_contact_substep_s = HUGE_VAL;
  /// Force-limited constraints: no constraint carries more than its yield force (the multiplier is
  /// clamped, as a motor's maximum impulse), so what the solve cannot hold flows plastically at the yield
  /// force and the plastic work is the energy the body took; a held point at its deviation cap then stops
  /// the core rigidly (the obstacle has reached the car's rigid part). Off: the solve carries whatever
  /// force the iterations reach and plasticity follows after the solve (docs/CRASH_CALIBRATION.md).
  bool yield_limited = false;
  /// Sleep: when no contact acts and every control point is slower than this [m/s] ...
  double sleep_speed_mps = 0.005;
  /// ... for this long [s], steps do no work until a contact, an impulse or a change of the inertial load
  /// wakes the body. A negative or infinite delay never sleeps.
  double sleep_delay_s = 0.5;
  /// Change of the inertial load (specific force [m/s^2], or angular velocity [rad/s] / angular
  /// acceleration [rad/s^2] times 1 m) since the body fell asleep that wakes it.
  double wake_load_mps2 = 0.05;
};

/// Whether this machine sweeps four side by side (SolverParams::wide_sweep: AVX2).
bool wideSweepAvailable();

/// Substeps for a step of `dt_s` asked to take `substeps`, none longer than `longest_s`: `substeps`, or
/// more (at most 4096). The relative slack keeps dt / h = 4.000...01 at 4.
uint32_t substepsNoLongerThan(double dt_s, uint32_t substeps, double longest_s);

/// Throws InputError naming the member for substeps or iterations of 0, or a negative or non-finite
/// damping, inertial scale or sleep speed.
void checkSolverParams(const SolverParams& params);

}  // namespace deform
