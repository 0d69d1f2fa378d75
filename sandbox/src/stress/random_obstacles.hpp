#pragma once
// The obstacles of the crash campaign (random_scenes.hpp): every type the scene schema has (wall, post,
// box, vegetation, ramp, mesh), sizes and masses across decades, in a car's path.
#include <nlohmann/json.hpp>

#include <string>

#include "stress/footprint.hpp"
#include "stress/random_draws.hpp"

namespace sandbox {

/// An obstacle's type and size, before it is placed.
struct ObstacleShape {
  std::string label;    ///< for the table: "wall", "post", "free box", "tree", "ramp", "drum", ...
  nlohmann::json keys;  ///< its scene keys but position_m and yaw_deg
  Eigen::Vector2d half_size_m{0, 0};  ///< footprint, in its own frame [m]
  double yaw_to_path_deg = 0;         ///< its turn from the car's heading [deg]
  double centre_height_m = 0;  ///< position_m's z: the centre of a box, 0 for what stands on its base [m]
  double ramp_length_m = 0;    ///< ramps: position_m is the low edge's middle, the footprint's centre
                               ///< half this further along its yaw [m]
};

/// A shape of a random type.
ObstacleShape drawObstacleShape(RandomDraws& draws);

/// Its footprint with its centre at `centre_m` and its yaw `yaw_deg` (world).
Footprint obstacleFootprint(const ObstacleShape& shape, const Eigen::Vector2d& centre_m, double yaw_deg);

/// Its scene object there: `keys` with position_m (rounded to 1 mm) and yaw_deg. `centre_m` is moved to
/// the rounded position, so that the footprint matches the file.
nlohmann::json placeObstacle(const ObstacleShape& shape, Eigen::Vector2d& centre_m, double yaw_deg);

}  // namespace sandbox
