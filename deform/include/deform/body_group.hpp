#pragma once
// Bodies in contact with each other (two cars), stepped as one: their substeps interleaved and the
// contacts between their surfaces solved in the same Gauss-Seidel sweeps as each body's own constraints.
// A contact between a control point of one body and a control triangle of the other moves both sides by
// their inverse masses (PBD, Mueller et al. 2007, eq. 8, with the triangle's corners weighted by the
// barycentric coordinates of the point over it): the momentum exchanged is equal and opposite, and no
// body leads the other.
#include <deform/deformable_body.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace deform {

/// Two bodies of a group that may touch: where body `b`'s frame lies in body `a`'s at the end of the
/// step, and how it moves relative to it. Through the substeps b's frame is placed back along its
/// velocity, as an obstacle is (StepInputs::contact_velocity_mps): a translation.
struct BodyLink {
  uint32_t a = 0, b = 1;  ///< indices into the group's bodies, a != b
  /// p_a = rotation_b_to_a p_b + translation_b_to_a_m, at the end of the step (a rotation matrix).
  Eigen::Matrix3d rotation_b_to_a = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation_b_to_a_m{0, 0, 0};
  /// Velocity of b's frame relative to a's, at a's core (BodySettings::core_m), in a's frame [m/s].
  Eigen::Vector3d velocity_mps{0, 0, 0};
  /// Angular velocity of b's frame relative to a's, in a's frame [rad/s].
  Eigen::Vector3d angular_velocity_radps{0, 0, 0};
  double friction = 0;  ///< Coulomb coefficient between the two surfaces [1]
};

/// What a link's contacts did over one step.
struct LinkReport {
  uint32_t contacts = 0;  ///< point-triangle pairs found penetrating, summed over the substeps
  /// Momentum the contacts gave a's points, in a's frame [N s]; b's points took minus it.
  Eigen::Vector3d impulse_on_a_Ns{0, 0, 0};
  /// Kinetic energy the contacts took from the two bodies' relative motion [J] (each body's report
  /// books it as its own contact loss, against the other's surface as its obstacle).
  double loss_J = 0;
  /// Deepest a place of one surface was found inside the other at a substep's start of contacts [m].
  double deepest_m = 0;
};

/// Steps `bodies` by dt_s, each with its own `inputs` (its obstacles, impulses, chassis motion), with the
/// contacts of `links` between them. Every body's report is as DeformableBody::step's, with the links'
/// contacts in its contact terms: contact_impulse_Ns, contact_moment_Nms, obstacle_work_J (the other
/// body's surface as the obstacle, its velocity relative to this body's frame), contact_work_J,
/// contact_loss_J and contact_points. The bodies share the largest substep count among them and sweep
/// the largest iteration count (a body with fewer stops sweeping its own constraints after its count).
/// A movable obstacle several bodies hold under one StepInputs::contact_keys entry is pushed by all of them
/// within each substep (by the sum of their pushes); its obstacle_displacement_m and
/// obstacle_velocity_change_mps are reported by the first body holding it only (zero in the others), so the
/// caller moves it once.
/// Throws InputError naming the link and field for a bad link, and as DeformableBody::step for bad inputs.
std::vector<StepReport> stepGroup(const std::vector<DeformableBody*>& bodies,
                                  const std::vector<const StepInputs*>& inputs,
                                  const std::vector<BodyLink>& links, double dt_s,
                                  std::vector<LinkReport>* link_reports = nullptr);

}  // namespace deform
