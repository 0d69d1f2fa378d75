#pragma once
// A scene as read from its JSON file (scenes/README.md lists every key, its unit and default): the
// cars with their meshes, starts, drive scripts and deformation knobs, the obstacles, the camera and
// what to write. Plain data, checked when it is read (scene_file.hpp); the runner plays it.
#include <vehicle/simulation.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace scenes {

/// The deformation knobs of one car (DESIGN.md section 6): a named preset, then any key overrides it.
/// The knobs are vehicle::DeformationSettings' members under the same names (coupling included).
struct DeformationConfig {
  std::string preset = "balanced";        ///< fast, balanced or accurate
  vehicle::DeformationSettings settings;  ///< the preset's values with the scene's keys applied
  /// skin_method `auto` (the default): settings.skin_method is deform::preferredSkinMethod of the car's
  /// control points and nearest points K, chosen again when a budget changes them (resolveSkinMethod).
  bool skin_method_auto = true;
};

/// Sets `d`'s skin method from its control points and K when it is `auto`.
void resolveSkinMethod(DeformationConfig& d);

/// Values of a named preset ("fast", "balanced" = vehicle's calibrated defaults, "accurate"): control
/// points, skin influences, substeps and iterations; nothing for another name.
std::optional<DeformationConfig> deformationPreset(const std::string& name);

/// One key of a drive script: the inputs at time t_s. Between keys, throttle, brake and steering are
/// interpolated linearly; handbrake and the speed-control mode hold from a key to the next.
struct DriveKey {
  double t_s = 0;       ///< time of the key [s]
  double throttle = 0;  ///< 0 .. 1 [-]
  double brake = 0;     ///< 0 .. 1 [-]
  double steering = 0;  ///< -1 (full right) .. 1 (full left) [-]
  bool handbrake = false;
  /// When set, throttle and brake come from a speed controller holding this speed until the next key
  /// [km/h]; throttle and brake of the key are then ignored.
  std::optional<double> target_speed_kmh;
};

/// Keys sorted by time. No keys: no input at all (the car coasts).
struct DriveScript {
  std::vector<DriveKey> keys;
};

/// Where and how fast a car starts.
struct StartConfig {
  Eigen::Vector3d position_m{0, 0, 0};  ///< ground point under the vehicle frame origin (z: lift) [m]
  double heading_deg = 0;               ///< about world Z, 0 faces +X [deg]
  double speed_kmh = 0;                 ///< forward speed at t = 0 [km/h]
  /// Sideways speed at t = 0 (+ to the car's left) [km/h]: a car sliding into a pole.
  double lateral_speed_kmh = 0;
  bool on_ground = true;  ///< lift the car so its tyres touch the ground at ride height
};

/// A deformable car.
struct VehicleConfig {
  std::string name;         ///< for the summary and timeline ("car0", ... by default)
  std::string mesh;         ///< builtin:... spec or a mesh file (absolute, or relative to the scene)
  double mesh_scale = 1.0;  ///< file units to metres [-]
  std::optional<std::string> mesh_up;       ///< file's up axis (+x, -y, ...); default per format
  std::optional<std::string> mesh_forward;  ///< file's forward axis; default per format
  /// Where the (force) wheels go when the model has no wheel parts: false, the vehicle library's
  /// bounding-box wheels (hubs under the body: a body without wheels); true, inside the bounding box with
  /// the tyres' bottoms 1 % of the height above its bottom (a mesh whose wheels are part of the body).
  bool wheels_in_body = false;
  double mass_kg = 1500;  ///< whole vehicle [kg]
  /// Points of the chassis's rigid collision hull (vehicle::VehicleSettings::collision_points).
  std::size_t collision_points = vehicle::VehicleSettings{}.collision_points;
  StartConfig start;
  DeformationConfig deformation;  ///< knobs and coupling (crush or visual)
  DriveScript drive;
  Eigen::Vector3f colour{0.62f, 0.08f, 0.06f};  ///< paint, sRGB [0, 1]
};

enum class ObstacleType : uint8_t { Wall, Post, Vegetation, Ramp, Box, Mesh };

/// A wall, post, bush, ramp, box or convex mesh (vehicle::World's obstacles). Which members count
/// depends on the type (scenes/README.md).
struct ObstacleConfig {
  ObstacleType type = ObstacleType::Wall;
  std::string name;
  /// Wall, Box, Mesh: centre (z defaults to half the height: standing on the ground); Post, Vegetation:
  /// base on the ground; Ramp: middle of its low edge [m].
  Eigen::Vector3d position_m{0, 0, 0};
  double yaw_deg = 0;                           ///< turn about world Z [deg]
  Eigen::Vector3d size_m{1, 1, 1};              ///< Wall, Box: full size [m]
  double radius_m = 0.127;                      ///< Post, Vegetation [m]
  double height_m = 1.5;                        ///< Post, Vegetation, Ramp [m]
  double length_m = 3.0;                        ///< Ramp: run along its rising direction [m]
  double width_m = 2.5;                         ///< Ramp [m]
  bool capsule = false;                         ///< Post: capsule instead of cylinder
  double mass_kg = 0;                           ///< Vegetation (> 0), Box and Mesh (0 = static) [kg]
  double friction = 0.6;                        ///< [-]
  std::string mesh;                             ///< Mesh: builtin spec or file
  double mesh_scale = 1.0;                      ///< Mesh [-]
  Eigen::Vector3f colour{0.55f, 0.55f, 0.55f};  ///< sRGB [0, 1]
};

enum class CameraMode : uint8_t {
  Chase,  ///< behind and above the followed car, turning with its heading
  Side,   ///< fixed eye, always looking at the followed car
  Fixed,  ///< fixed eye and target
};

struct CameraConfig {
  CameraMode mode = CameraMode::Chase;
  std::size_t follow = 0;               ///< index of the car followed [-]
  double distance_m = 9.0;              ///< Chase: behind the car [m]
  double height_m = 3.0;                ///< Chase: above the car's origin [m]
  Eigen::Vector3d eye_m{0, -10, 2};     ///< Side, Fixed: camera position [m]
  Eigen::Vector3d target_m{0, 0, 0.7};  ///< Fixed: point looked at [m]
  double fov_deg = 35.0;                ///< vertical field of view [deg]
};

struct OutputConfig {
  bool frames = false;   ///< PNG per frame
  bool video = false;    ///< MP4
  bool heatmap = false;  ///< colour the car by its displacement
  int width = 1280;      ///< [px]
  int height = 720;      ///< [px]
  double fps = 30;       ///< frames per second of the pictures and the timeline [1/s]
  /// Simulated seconds per second of video: 1 real time, 0.25 four times slower [-].
  double playback_speed = 1.0;
  /// Displacement shown red by the heat map [m]; 0: the car's max_deviation_m.
  double heatmap_full_scale_m = 0.0;
  int samples = 4;  ///< multisampling per pixel [-]
};

struct SceneConfig {
  std::string name;              ///< the file's stem unless given
  std::string description;       ///< one line: what the scene shows
  std::string source;            ///< the file it came from (for messages)
  double duration_s = 1;         ///< simulated time [s]
  double physics_hz = 500;       ///< fixed physics rate [Hz]
  double gravity_mps2 = 9.81;    ///< downwards [m/s^2]
  bool ground = true;            ///< a ground plane at z = 0
  double ground_friction = 1.0;  ///< [-]
  /// Threads the cars' deformation steps run on (scene key threads, sandbox run --threads); none: the
  /// machine's cores. The state does not depend on it.
  std::optional<int> threads;
  /// Deformation budget per physics step, every car together (scene key deformation_budget_ms, sandbox
  /// run --budget-ms): each car's level of detail is chosen for it (deformation_budget.hpp) [ms].
  std::optional<double> deformation_budget_ms;
  std::vector<VehicleConfig> vehicles;
  std::vector<ObstacleConfig> obstacles;
  CameraConfig camera;
  OutputConfig outputs;
  /// FNV-1a of the scene's resolved keys (the file with every --set applied) less camera, outputs and
  /// description, which do not change the simulation: what a saved state must have been saved with.
  uint64_t settings_hash = 0;
};

}  // namespace scenes
