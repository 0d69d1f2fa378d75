#pragma once
// One car in a World: an ODE rigid chassis (mass and inertia of its hull, collision shape its control
// mesh as an ODE convex geom) driven by forces at its wheels (tyre_model.hpp). Made by World::addCar;
// lives as long as its World.
#include <vehicle/driver_input.hpp>
#include <vehicle/obstacle_shape.hpp>
#include <vehicle/pose.hpp>
#include <vehicle/tyre_model.hpp>
#include <vehicle/vehicle_settings.hpp>

#include <deform/control_mesh.hpp>

#include <Eigen/Core>
#include <memory>
#include <vector>

struct dxBody;
struct dxGeom;
struct dxSpace;
struct dxWorld;

namespace vehicle {

class StateWriter;
class StateReader;
namespace ode {
class GeomGrid;
}

/// What a wheel is doing, for the renderer (turning, steering, riding wheels) and for metrics.
struct WheelState {
  double steer_angle_rad = 0;                ///< angle about the chassis Z axis, + turns left [rad]
  double rotation_rad = 0;                   ///< rolling angle about the axle, in [0, 2 pi) [rad]
  TyreState tyre;                            ///< spin [rad/s] and tread deflections
  double compression_m = 0;                  ///< suspension compression from full extension [m]
  double normal_load_N = 0;                  ///< suspension force pressing the tyre on the ground [N]
  bool in_contact = false;                   ///< the suspension ray hit something within its length
  bool sliding = false;                      ///< the tyre is at its friction limit
  bool locked = false;                       ///< brakes hold the wheel still
  double slip_ratio = 0;                     ///< kappa' [-]
  double slip_angle_rad = 0;                 ///< alpha' [rad]
  Eigen::Vector3d contact_point_m{0, 0, 0};  ///< where the tyre touches (world) [m]
  Eigen::Vector3d contact_normal{0, 0, 1};   ///< surface normal there (world)
  Eigen::Vector3d force_N{0, 0, 0};          ///< total force of this wheel on the chassis (world) [N]
  double drive_torque_Nm = 0;                ///< the engine's torque on this wheel in the last step [N m]
};

class Car {
 public:
  Car(const Car&) = delete;
  Car& operator=(const Car&) = delete;
  ~Car();

  const VehicleSettings& settings() const { return settings_; }
  /// The wheels as driven (settings, model or bounding box), vehicle frame.
  const std::vector<WheelSettings>& wheelSettings() const { return wheel_settings_; }

  /// Pedals and steering from now on (clamped to their ranges).
  void setInput(const DriverInput& input);
  const DriverInput& input() const { return input_; }

  double mass_kg() const { return settings_.mass_kg; }  ///< the whole car [kg]
  /// Inertia of the whole car about the centre of mass in the chassis axes [kg m^2].
  const Eigen::Matrix3d& inertia_kg_m2() const { return inertia_kg_m2_; }
  /// The ODE chassis body's mass and inertia: the whole car's less what a deformable shell carries on its
  /// own point masses (carryShell) [kg], [kg m^2].
  double chassisMass_kg() const { return chassis_mass_kg_; }
  const Eigen::Matrix3d& chassisInertia_kg_m2() const { return chassis_inertia_kg_m2_; }
  /// Hands `shell_mass_kg` with inertia `shell_inertia_kg_m2` (about the centre of mass, chassis axes) to
  /// a deformable shell whose points move on their own and pull on the chassis through their constraints:
  /// the ODE body keeps the rest, so the car's total mass is counted once. Throws deform::InputError if
  /// the rest is not a positive mass with a positive-definite inertia.
  void carryShell(double shell_mass_kg, const Eigen::Matrix3d& shell_inertia_kg_m2);
  /// Centre of mass in the vehicle (mesh) frame [m]: the chassis body's origin.
  const Eigen::Vector3d& centreOfMass_m() const { return centre_of_mass_m_; }

  /// Pose of the chassis body (origin at the centre of mass).
  Pose bodyPose() const;
  /// Pose of the vehicle frame (the mesh's coordinates): where to draw the mesh, and the frame the
  /// deformation state lives in.
  Pose vehiclePose() const;
  Eigen::Vector3d velocity_mps() const;           ///< of the centre of mass (world) [m/s]
  Eigen::Vector3d angularVelocity_rad_s() const;  ///< (world) [rad/s]
  double forwardSpeed_mps() const;                ///< velocity along the chassis X axis [m/s]

  const std::vector<WheelState>& wheels() const { return wheels_; }
  /// World pose of wheel `i`'s hub: steering about the chassis Z, rolling about the axle (Y), riding
  /// on its suspension.
  Pose wheelPose(std::size_t i) const;
  /// Current bicycle-model steering angle of the front axle [rad].
  double steerAngle_rad() const { return steer_rad_; }
  /// Wheelbase and front track the Ackermann geometry uses [m].
  double wheelbase_m() const { return wheelbase_m_; }
  double track_m() const { return track_m_; }

  /// The collision hull in the vehicle frame (the control mesh it was built from).
  const deform::ControlMesh& collisionHull() const { return hull_; }
  /// Replaces the collision shape (e.g. by the crushed rest shape) without touching mass or inertia.
  void setCollisionHull(const deform::ControlMesh& hull);
  /// The chassis shape in the world, for other cars' crush queries (Convex).
  ObstacleShape shape() const;

 private:
  friend class World;
  struct ConvexGeom;
  Car(dxWorld* world, dxSpace* space, void* geom_data, const deform::ControlMesh& hull,
      const VehicleSettings& settings, std::vector<WheelSettings> wheels, const Pose& vehicle_pose,
      const Eigen::Vector3d& velocity_mps);
  /// Steering, engine, wheels (ray, suspension, tyre) and drag forces for a step of dt_s; the wheels'
  /// rays meet the geoms `geoms` (World's, built this step) finds near them.
  void applyForces(double dt_s, const ode::GeomGrid& geoms);
  /// The ODE body's mass and inertia (about its origin, the centre of mass).
  void setChassisMass(double mass_kg, const Eigen::Matrix3d& inertia_kg_m2);
  /// Everything a step changes (World::saveState): the chassis body's motion, steering, driver input,
  /// every wheel's state and the collision hull (replaced when the dent is re-hulled).
  void saveState(StateWriter& out) const;
  /// Puts back what saveState wrote; the backstop geoms are the World's to rebuild. Throws
  /// deform::InputError (through `in`) for bytes that do not fit this car.
  void restoreState(StateReader& in);
  /// The car's geoms in the space, in a fixed order: the hull, then the backstop's.
  void appendGeoms(std::vector<dxGeom*>& out) const;
  /// The crush backstop (World::setCrushAllowance): a second convex geom on the chassis, the collision
  /// hull with every point moved `allowance_m` towards the centre of mass (then re-hulled), tagged with
  /// `geom_data`; none for an allowance of 0.
  void setCoreHull(double allowance_m, void* geom_data);
  /// The crush backstop as the car's rigid parts (World::setRigidParts): one box geom on the chassis per
  /// box (vehicle frame), tagged with `geom_data`; none for no boxes.
  void setCoreBoxes(const std::vector<deform::Aabb>& boxes_m, void* geom_data);
  void clearCore();
  /// One backstop geom: the convex hull of `points_body_m` (relative to the centre of mass).
  void addCoreGeom(const std::vector<Eigen::Vector3d>& points_body_m, void* geom_data);

  VehicleSettings settings_;
  std::vector<WheelSettings> wheel_settings_;
  std::vector<Eigen::Vector3d> mount_body_m_;  ///< suspension mounts, body frame [m]
  deform::ControlMesh hull_;
  Eigen::Vector3d centre_of_mass_m_{0, 0, 0};
  Eigen::Matrix3d inertia_kg_m2_ = Eigen::Matrix3d::Identity();
  double chassis_mass_kg_ = 0;
  Eigen::Matrix3d chassis_inertia_kg_m2_ = Eigen::Matrix3d::Identity();
  double wheelbase_m_ = 0, track_m_ = 0;

  DriverInput input_;
  double steer_rad_ = 0;
  std::vector<WheelState> wheels_;

  dxSpace* space_ = nullptr;
  dxBody* body_ = nullptr;
  dxGeom* ray_ = nullptr;
  std::vector<int> ray_candidates_;  ///< scratch of applyForces: the geoms near a wheel's ray
  std::unique_ptr<ConvexGeom> convex_;
  std::vector<std::unique_ptr<ConvexGeom>> core_;  ///< crush backstop geoms (none: no backstop)
};

}  // namespace vehicle
