#pragma once
// What acts on a deformable body during one step, all in the vehicle frame.
#include <deform/contact_shapes.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

namespace deform {

/// An impulse on one control point, applied at the start of the step.
struct PointImpulse {
  uint32_t point = 0;                   ///< control point
  Eigen::Vector3d impulse_Ns{0, 0, 0};  ///< [N s]
};

/// The chassis's motion, for the inertial (fictitious) forces on the control points in the vehicle
/// frame, which accelerates and rotates: a = g - a_c - alpha x r - omega x (omega x r) - 2 omega x v,
/// r from the core, v relative to the chassis (scaled by SolverParams::inertial_scale).
struct ChassisMotion {
  Eigen::Vector3d acceleration_mps2{0, 0, 0};            ///< of the core, in the vehicle frame [m/s^2]
  Eigen::Vector3d angular_velocity_radps{0, 0, 0};       ///< [rad/s]
  Eigen::Vector3d angular_acceleration_radps2{0, 0, 0};  ///< [rad/s^2]
  Eigen::Vector3d gravity_mps2{0, 0, 0};                 ///< in the vehicle frame; 0 = no sag [m/s^2]
};

/// Everything that acts on the body during one step (DeformableBody::step), in the vehicle frame.
struct StepInputs {
  /// Obstacles this step, where they are at the END of the step (vehicle frame).
  std::vector<ContactShape> contacts;
  /// Per entry of `contacts` (missing entries: at rest): the velocity relative to the vehicle frame of the
  /// obstacle's point at the body's core (BodySettings::core_m), in the vehicle frame [m/s]. deform moves
  /// each obstacle along it through its substeps (translation), so one that closes v dt during the step
  /// pushes the points at v, not all at once.
  std::vector<Eigen::Vector3d> contact_velocity_mps;
  /// Per entry of `contacts` (missing entries: 0): the obstacle's angular velocity relative to the vehicle
  /// frame [rad/s] (a wall seen from a pitching car turns at minus the car's rate). The obstacle's surface
  /// at p then moves at contact_velocity + w x (p - core_m): friction holds a point to that motion and the
  /// contact work and loss are taken against it. The obstacle's placement in the substeps stays a
  /// translation.
  std::vector<Eigen::Vector3d> contact_angular_velocity_radps;
  /// Per entry of `contacts` (missing entries: 0): when set, the obstacle is also met between the control
  /// points: points of the control surface (triangle centroids, edge midpoints) found inside it push the
  /// corners around them out (face contacts). For a broad body such as another car, whose flat front can
  /// meet this body between its points and would otherwise pass into it; a post is better left to the
  /// points (it makes a narrow notch between them, as a pole does).
  std::vector<uint8_t> surface_contact;
  /// Per entry of `contacts` (missing entries: 0, immovable): the obstacle's inverse mass [1/kg]. A free
  /// obstacle (a pushed box, a tree) is a particle inside the substeps, as a finite core is: each contact
  /// correction moves it back by its share (PBD's inverse-mass weights, Mueller et al. 2007, eq. 8), its
  /// velocity changes with it, and the step reports how far it moved off its path and its velocity change
  /// (StepReport::obstacle_displacement_m, obstacle_velocity_change_mps) for the caller to hand to its rigid
  /// body. Its turn is not changed within the step. A light obstacle
  /// taken as immovable inside the step gets the momentum that would stop the body's points, and is thrown
  /// (a 10 kg box pinched between a car and a wall: 250 kJ of the obstacle's work from a 52 kJ impact).
  std::vector<double> contact_inverse_mass_per_kg;
  /// Per entry of `contacts` (missing entries: none): for a movable obstacle, the unit normals (vehicle
  /// frame) of what holds it (the ground, a wall it rests against: its caller's contacts with immovable
  /// things), out of them. The body cannot push it into them: pinched between the body and a wall, a box
  /// gives way only along the wall, and the wall takes the rest of the push.
  std::vector<std::vector<Eigen::Vector3d>> contact_held_normals;
  /// Per entry of `contacts` (missing entries: 0): which movable obstacle it is, for the bodies stepped as
  /// one (stepGroup). Entries of several bodies with the same non-zero key are one obstacle, pushed by all
  /// of them within each substep: a box pinched between two cars gives way to the sum of their pushes, not
  /// to each car's as if the other were not there (each car then moved it by its own push, and both cars
  /// left 12 % of their impact energy unexplained). `frame_to_world` turns the bodies' frames into one.
  std::vector<uint64_t> contact_keys;
  /// The body's frame's orientation in a frame common to the bodies of a group (a rotation matrix): only
  /// for sharing movable obstacles (contact_keys).
  Eigen::Matrix3d frame_to_world = Eigen::Matrix3d::Identity();
  /// Coulomb friction coefficient between the control points and every obstacle [1]; 0 = frictionless.
  /// Off by default: on fine control meshes (thousands of points) pressed against a wall, position-level
  /// friction with one Gauss-Seidel iteration was seen to jitter (an open issue).
  double contact_friction = 0.0;
  std::vector<PointImpulse> impulses;  ///< point impulses
  ChassisMotion chassis;               ///< for inertial forces
  /// Mass of the core (the chassis that the spokes hold the points to) [kg]. Finite: the core is a heavy
  /// particle inside the substeps, pushed back by every force the body puts on it, and the step reports
  /// how far it moved and the momentum it took (StepReport::core_*), for the caller to hand to its
  /// rigid body. Infinite (the default): the core is kinematic; the momentum it took is still reported.
  double core_mass_kg = std::numeric_limits<double>::infinity();
  /// The inverse inertia of the rigid assembly that the core stands for (a car: chassis and shell turning
  /// together) about `core_centre_of_mass_m`, in this body's frame [1/(kg m^2)]. The rigid stop at the
  /// caps (a held point at its cap stops the core) acts at the held points, off the centre of mass: it
  /// takes the turn its moment gives into account, so that it stops the point of the core it acts at
  /// instead of reversing it (with the core taken as not turning, a stop at a door's far corner threw a car
  /// back at several times its impact energy). Zero: the core does not turn (the moment is still reported).
  Eigen::Matrix3d core_inverse_inertia_per_kg_m2 = Eigen::Matrix3d::Zero();
  /// Where that assembly's centre of mass is, in this body's frame at rest [m].
  Eigen::Vector3d core_centre_of_mass_m = Eigen::Vector3d::Zero();
};

}  // namespace deform
