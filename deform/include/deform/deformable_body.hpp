#pragma once
// A deformable car body: shared settings, its own state and the XPBD solver that steps it
// (Macklin, Mueller, Chentanez 2016; substeps after Macklin et al. 2019; Kenwright 2015 "Dynamics").
// One step, in the vehicle frame:
//   impulses -> for each substep: predict (damping, inertial forces), find contacts, `iterations` sweeps
//   of edges, spokes, bends and contacts, the shell orientation, the visual constraint (the last
//   projection), plasticity (rest lengths only), v = (x - x_prev) / h.
#include <deform/body_settings.hpp>
#include <deform/body_state.hpp>
#include <deform/solver_params.hpp>
#include <deform/step_inputs.hpp>

#include <array>
#include <limits>
#include <memory>
#include <vector>

namespace deform {

/// What one step did.
struct StepReport {
  /// The step did no work: the shell moved with its core as one rigid body, and core_impulse_Ns and
  /// core_angular_impulse_Nms are what holding it against its inertial load (gravity, the chassis's
  /// acceleration and rotation) hands the core.
  bool asleep = false;
  uint32_t contact_points = 0;  ///< control points found inside an obstacle (summed over substeps)
  double plastic_work_J = 0;    ///< plastic work done during the step [J]
  double max_speed_mps = 0;     ///< fastest control point at the end, relative to the chassis [m/s]
  /// Momentum the body handed the core over the step: the spokes' pull, the visual constraint's, the
  /// shell orientation's and the damping's reactions (vehicle frame) [N s]. Equal and opposite to the
  /// momentum those took from the points.
  Eigen::Vector3d core_impulse_Ns{0, 0, 0};
  /// Angular momentum about the core the shell orientation constraint handed the core [N m s].
  Eigen::Vector3d core_angular_impulse_Nms{0, 0, 0};
  /// How far the core moved during the step, and its velocity at the end, relative to its kinematic path
  /// (zero for an infinite core mass) [m], [m/s]. The state is re-centred on the core afterwards.
  Eigen::Vector3d core_displacement_m{0, 0, 0};
  Eigen::Vector3d core_velocity_mps{0, 0, 0};
  /// Momentum the obstacles gave the points (contact push-out and friction, face contacts) [N s].
  Eigen::Vector3d contact_impulse_Ns{0, 0, 0};
  /// The same per entry of StepInputs::contacts, for the reaction on each obstacle [N s].
  std::vector<Eigen::Vector3d> contact_impulse_per_obstacle_Ns;
  /// Per entry of StepInputs::contacts: how far a movable obstacle (StepInputs::contact_inverse_mass_per_kg)
  /// ended the step from where its input velocity put it, by the body's push [m] (0 for an immovable one).
  std::vector<Eigen::Vector3d> obstacle_displacement_m;
  /// Per entry of StepInputs::contacts: a movable obstacle's velocity change by the body's push [m/s]. Times
  /// its mass it is minus contact_impulse_per_obstacle_Ns, unless something holds it
  /// (StepInputs::contact_held_normals): the holder takes the rest.
  std::vector<Eigen::Vector3d> obstacle_velocity_change_mps;
  /// Energy the viscous damping took out of the points' motion relative to the core [J].
  double damping_loss_J = 0;
  /// Work the obstacles did on the points, sum of J . V over every contact correction (impulse J, the
  /// obstacle's velocity V relative to the chassis) [J]: what the obstacles put into the body.
  double contact_work_J = 0;
  /// The same in the step's own frame (the chassis as the step began, in which StepInputs gives the
  /// obstacles' motion; the core moving within it is not subtracted), rigid stops at the cap included [J].
  /// With contact_impulse_Ns and contact_moment_Nms a caller has the obstacles' work in any frame: in the
  /// world, with the chassis's velocity v at core_m and its turn w, W + J . v + M . w (zero for an obstacle
  /// at rest in the world).
  double obstacle_work_J = 0;
  /// Angular impulse about core_m of everything the obstacles did (contact_impulse_Ns's moment) [N m s].
  Eigen::Vector3d contact_moment_Nms{0, 0, 0};
  /// Work the inertial (fictitious) forces of the chassis's motion and gravity did on the points' motion
  /// relative to the chassis, sum m a . travel over the predictions [J]: what a chassis stopped by
  /// something else than the body (ODE's rigid contact) puts into the shell.
  double inertial_work_J = 0;
  /// Kinetic energy the contact corrections took from the points in each obstacle's frame [J]: the
  /// inelastic stop of the motion into it, and friction.
  double contact_loss_J = 0;
};

/// Energy of the body relative to the chassis (the core is kinematic).
struct BodyEnergy {
  double kinetic_J = 0;  ///< sum 1/2 m v^2 [J]
  double elastic_J = 0;  ///< sum 1/2 C^2 / alpha over compliant constraints (XPBD eq. 4) [J]
  double total_J() const { return kinetic_J + elastic_J; }
};

/// Kinetic and elastic energy of `state` relative to the chassis [J].
BodyEnergy bodyEnergy(const BodySettings& settings, const BodyState& state);

/// Largest |x - x0| over the control points [m].
double maxDeviation(const BodySettings& settings, const BodyState& state);

/// The constraint residual: RMS over every edge, spoke and bend of the strain (l - L) / L against the
/// current rest lengths [-]. A settled body free of contact has none; what is left is an unconverged solve
/// or stress locked in by the visual constraint.
double constraintStrainRms(const BodySettings& settings, const BodyState& state);

/// One deformable body: shared immutable settings, its own state, and the XPBD step that moves it. Step it
/// once per engine step with the obstacles in its frame; read the reaction on the core from the report.
class DeformableBody {
 public:
  /// Throws InputError for bad solver parameters.
  explicit DeformableBody(std::shared_ptr<const BodySettings> settings, const SolverParams& params = {});

  /// Advances by dt_s [s]. Throws InputError naming "dt_s" for a time step that is zero, negative or
  /// not finite, and naming the input for a non-finite impulse, an impulse on an unknown point or a bad
  /// contact shape.
  StepReport step(const StepInputs& inputs, double dt_s);

  const BodySettings& settings() const { return *settings_; }  ///< the shared, immutable part
  const BodyState& state() const { return state_; }            ///< positions, rest lengths, time now
  /// Replaces the state (a restored snapshot or a decoded damage record); sizes must match.
  void setState(BodyState state);
  const SolverParams& params() const { return params_; }  ///< substeps, iterations, damping, sleep
  /// Elastic energy at the forces the last substep's solve carried, sum 1/2 alpha F^2 with F = |lambda| /
  /// h^2 (XPBD eq. 18) [J]. Equal to 1/2 C^2 / alpha (bodyEnergy) where the solve converged; where it did
  /// not (a stiff constraint on light points), C is mostly error the solve has not yet corrected, not
  /// stored energy, and this is what the body holds. 0 before the first step.
  double carriedElasticEnergy_J() const;
  /// Throws InputError for bad parameters.
  void setParams(const SolverParams& params);

 private:
  // A step in stages: step() runs them in order; BodyGroup (body_group.hpp) interleaves the substeps of
  // bodies in contact with each other, so that their contacts are solved in the same sweeps.
  friend class BodyGroup;
  /// Checks the inputs and starts a step of dt_s. False when the body sleeps through it (report_ is then
  /// complete). `touched`: something outside `inputs` (another body of a group) is in reach, so the body
  /// must not sleep through the step.
  bool beginStep(const StepInputs& inputs, double dt_s, bool touched);
  /// Substep k (1 .. substeps): the obstacles placed, the prediction, the contacts found, the multipliers
  /// zeroed.
  void beginSubstep(uint32_t k);
  /// One Gauss-Seidel sweep of the constraints and of the obstacles' contacts.
  void iterate();
  /// After the sweeps: the shell orientation, the visual constraint, plasticity and the contact loss.
  void settleSubstep();
  /// Velocities from positions, and the substep's sums into report_.
  void endSubstep();
  /// Zeroes the multipliers of half `half` of the sweep (0: also those across the cut).
  void clearMultipliers(int half);
  /// The core re-centred, the sleep bookkeeping; hands back the step's report.
  StepReport endStep();
  template <bool kLimited>
  void sweepConstraints();
  void refreshDistanceFactors();  ///< edge_factors_, bend_factors_, column_factors_ for h_s_ and the core
  /// Books a correction `dx` of point `i` by obstacle `shape` (its momentum, work and moment).
  void movedBy(uint32_t shape, uint32_t i, const Eigen::Vector3d& dx);

  // The step in progress (between beginStep and endStep).
  const StepInputs* inputs_ = nullptr;
  StepReport report_;
  double dt_s_ = 0, h_s_ = 0;
  uint32_t substeps_ = 1;  ///< this step's (a group's may exceed params_.substeps)
  /// The substep in progress: the core inside it and the sums its corrections build up.
  struct SubstepSums {
    Eigen::Vector3d core{0, 0, 0}, core_start{0, 0, 0};
    Eigen::Vector3d to_core_Ns{0, 0, 0};
    /// sum of lever x m_i dx_i, the lever a point on the line the correction acts along (a spoke's
    /// anchor, a column's rest place): the spokes' moment on the points
    Eigen::Vector3d spoke_twist{0, 0, 0};
    Eigen::Vector3d spoke_pull_Ns{0, 0, 0};  ///< sum over spokes of m_i dx_i: their momentum x h
    Eigen::Vector3d contact_push{0, 0, 0};   ///< sum of m_i dx_i by the obstacles
    Eigen::Vector3d tie_push{0, 0, 0};  ///< sum of m_i dx_i by the shell orientation and visual constraints
    double contact_work_x_h = 0, obstacle_work_x_h = 0;
    Eigen::Vector3d contact_moment_x_h{0, 0, 0};
  };
  SubstepSums sub_;
  /// Fills contacts_; returns how many points are inside an obstacle.
  uint32_t findContacts(const std::vector<ContactShape>& shapes, const StepInputs& inputs, double h);
  /// `shapes` moved back along their velocities to where they are `behind_s` before the step's end.
  void placeObstacles(const StepInputs& inputs, double behind_s);
  void plasticity(StepReport& report, const Eigen::Vector3d& core_m, double h);
  bool loadChanged() const;
  /// Every constraint's yield force and elastic band from the state's rest lengths (after construction,
  /// setState and setParams).
  void refreshYieldForces();
  /// One crush column's cached yield growth and clamp (column_taken_m_, column_bottomed_).
  void refreshColumn(std::size_t k);
  /// The visual constraint (the deviation cap) after the solve; a held point at its cap stops the core.
  void capDeviation(double h, const StepInputs& inputs, Eigen::Vector3d& core,
                    const Eigen::Vector3d& core_start, Eigen::Vector3d& tie_push, StepReport& report);
  /// Asleep: the core's impulse and moment from holding the rigid shell against its inertial load, a core
  /// of finite mass carried along with the shell. O(1) per step: the shell's mass moments are taken once when
  /// it falls asleep (positions are frozen).
  void rigidShellLoad(double dt_s, double core_mass_kg, StepReport& report);

  /// Mass moments of the frozen shell about the core: mass, first moment and inertia tensor.
  struct RigidMoments {
    bool valid = false;
    double mass_kg = 0;
    Eigen::Vector3d first_moment_kgm{0, 0, 0};
    Eigen::Matrix3d inertia_kgm2 = Eigen::Matrix3d::Zero();
  };
  RigidMoments rigid_moments_;
  /// Sum over the columns (or spokes) of w_core / (w_point + w_core): the share of its correction each
  /// hands the core, summed. Above 1 (a shell heavier than its core) their summed move overshoots.
  double core_share_sum_ = 0;
  /// max(1, shell mass x w_core): by how much the drag's summed reaction on the core would overshoot.
  double drag_split_ = 1;
  /// The core mass the two above were found for [kg] (NaN: not yet).
  double overshoot_core_mass_kg_ = std::numeric_limits<double>::quiet_NaN();
  double last_substep_s_ = 0;  ///< h of the last substep (carriedElasticEnergy_J)
  /// carriedElasticEnergy_J of the last substep, or negative until asked (a sleeping body's stays).
  mutable double carried_elastic_J_ = -1;

  /// A support shape moved by `offset_m` (an obstacle part way along its path through the step).
  struct ShiftedSupport {
    ConvexSupportShape shape;
    Eigen::Vector3d offset_m{0, 0, 0};
    static Eigen::Vector3d support(const void* user, const Eigen::Vector3d& direction);
  };

  /// A contact for one substep: point `point` must stay on the outer side of the plane through
  /// `surface_m` with unit normal `normal`.
  struct ContactPoint {
    uint32_t shape;  ///< index into the step's contacts
    uint32_t point;
    Eigen::Vector3d normal;
    Eigen::Vector3d surface_m;
    /// Where the point began the substep, carried along with the obstacle's surface (friction's anchor).
    Eigen::Vector3d carried_start_m;
    Eigen::Vector3d moved_m{0, 0, 0};  ///< the correction's displacement of the point this substep
  };

  /// A point of the control surface between `corners` (at barycentric `bary`) inside an obstacle: it
  /// must come out to the plane through `surface_m` with unit `normal` (out of the obstacle).
  struct FaceContact {
    uint32_t shape;  ///< index into the step's contacts
    std::array<uint32_t, 3> corners;
    Eigen::Vector3d bary;
    Eigen::Vector3d normal;
    Eigen::Vector3d surface_m;
    std::array<Eigen::Vector3d, 3> moved_m{
        Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
        Eigen::Vector3d::Zero()};  ///< the correction's displacement of each corner this substep
  };
  /// Kinetic energy the contact corrections took from the points this substep, in each obstacle's frame
  /// (call before the velocities are updated) [J].
  double contactLoss(const StepInputs& inputs, double h) const;
  /// The velocity of obstacle `shape`'s surface at `p_m`, relative to the vehicle frame (StepInputs).
  Eigen::Vector3d obstacleVelocity(const StepInputs& inputs, uint32_t shape,
                                   const Eigen::Vector3d& p_m) const;
  /// Appends the face contacts of one obstacle; returns how many.
  uint32_t findFaceContacts(const ContactShape& shape, uint32_t shape_index, const StepInputs& inputs,
                            double h);

  std::shared_ptr<const BodySettings> settings_;
  SolverParams params_;
  BodyState state_;
  // Scratch, not state: reset every substep.
  std::vector<Eigen::Vector3d> previous_m_;
  std::vector<double> edge_lambda_, spoke_lambda_, bend_lambda_;
  std::vector<Eigen::Vector3d> column_lambda_;
  /// The edges', bends' and columns' (or spokes') step factors (distanceFactors) for substeps of
  /// factors_h_s_ [s] and a core of inverse mass factors_core_per_kg_ (the columns').
  std::vector<DistanceFactors> edge_factors_, bend_factors_, column_factors_;
  double factors_h_s_ = 0, factors_core_per_kg_ = 0;
  /// The edges' and bends' two points interleaved, and where four neighbours in the sweep share no point
  /// (deform/src/sweep_wide.hpp: they are swept side by side).
  std::vector<uint32_t> edge_pairs_, bend_pairs_;
  std::vector<uint8_t> edge_disjoint_, bend_disjoint_;
  /// Whether column k holds point k for every k (the column sweep then reads four in a row as rows).
  bool columns_in_point_order_ = false;
  /// Scratch of plasticity, per half: the constraints outside their elastic band and their squared lengths.
  std::vector<uint32_t> outside_[2];
  std::vector<double> outside_m2_[2];
  std::vector<YieldForce> edge_yield_N_, spoke_yield_N_, bend_yield_N_;  ///< what each carries at most
  std::vector<ElasticBand> edge_band_, spoke_band_, bend_band_;          ///< where each stays elastic (cache)
  /// Per crush column, from its rest place (cache): the yield hardening has added [m], and whether it has
  /// crushed to its clamp (bottomed out, rigid inward).
  std::vector<double> column_taken_m_;
  std::vector<uint8_t> column_bottomed_;
  std::vector<ContactPoint> contacts_;
  std::vector<ContactPoint> contacts_of_half_[2];  ///< findContacts' scratch: each half's, in point order
  std::vector<uint32_t> near_shape_of_half_[2];    ///< findContacts' scratch: the points not surely apart
  std::vector<FaceContact> face_contacts_;
  /// A point an obstacle's contact moved this substep (capDeviation): the obstacle and its normal.
  struct HeldPoint {
    uint32_t point, shape;
    Eigen::Vector3d normal;
  };
  std::vector<HeldPoint> held_;
  /// The turn the rigid stops at the caps gave the core this step (capDeviation) [rad/s].
  Eigen::Vector3d stop_omega_radps_ = Eigen::Vector3d::Zero();
  std::vector<uint32_t> near_cap_of_half_[2];  ///< capDeviation's scratch: each half's, in point order
  std::vector<ContactShape> placed_;           ///< the obstacles where they are in the current substep
  /// Per obstacle, this step: its inverse mass [1/kg] (0: immovable), and for a movable one its
  /// displacement off its input path at the substep's start [m], its velocity change [m/s], and the
  /// displacement this substep's contact corrections gave it so far [m].
  std::vector<double> obstacle_inverse_mass_;
  std::vector<Eigen::Vector3d> obstacle_offset_m_, obstacle_dv_mps_, obstacle_shift_m_;
  std::vector<std::vector<Eigen::Vector3d>> obstacle_held_;  ///< StepInputs::contact_held_normals, unit
  /// What of the move `move_m` a movable obstacle may make now, held back by what holds it (it does not
  /// go into a held normal's thing) [m].
  Eigen::Vector3d heldMove(uint32_t shape, const Eigen::Vector3d& move_m) const;
  /// `v` without its components into obstacle `shape`'s held normals.
  Eigen::Vector3d heldBack(uint32_t shape, Eigen::Vector3d v) const;
  std::vector<ShiftedSupport> shifted_;  ///< storage behind placed_'s support shapes (stable addresses)
  // The core inside a step: displacement and velocity relative to its kinematic path, its inverse mass.
  Eigen::Vector3d core_shift_m_{0, 0, 0}, core_velocity_mps_{0, 0, 0};
  double core_inverse_mass_per_kg_ = 0;
  /// This step's inertial inputs, unscaled: g - a_c [m/s^2], omega [rad/s], alpha [rad/s^2].
  Eigen::Vector3d load_mps2_{0, 0, 0}, omega_radps_{0, 0, 0}, alpha_radps2_{0, 0, 0};
  double radius_m_ = 0;  ///< longest spoke at rest: reach of the angular terms [m]
};

}  // namespace deform
