#pragma once
// An obstacle's shape as the deformation side queries it for the crush coupling (DESIGN.md section 5):
// an exact primitive (half-space, sphere, box, capsule) or a convex shape given by its support function
// (cylinder, convex vertices), in explicit coordinates of one frame (the world, or a car's vehicle frame
// after transformShape). Plain data: no ODE in sight.
#include <vehicle/pose.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace vehicle {

enum class ShapeType : uint8_t {
  HalfSpace,  ///< solid below the plane normal . x = offset_m (the ground); no support function
  Sphere,     ///< centre_m, radius_m
  Box,        ///< centre_m, axes, half_extents_m
  Capsule,    ///< segment a_m-b_m swept by radius_m
  Cylinder,   ///< axis a_m-b_m (the two flat ends' centres), radius_m
  Convex,     ///< convex hull of vertices_m (centre_m is their centroid, inside)
};

struct ObstacleShape {
  ShapeType type = ShapeType::Box;
  Eigen::Vector3d normal{0, 0, 1};                     ///< HalfSpace: unit outward normal of the surface
  double offset_m = 0;                                 ///< HalfSpace: the plane is normal . x = offset_m [m]
  Eigen::Vector3d centre_m{0, 0, 0};                   ///< Sphere, Box, Convex: centre (inside) [m]
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< Box: columns are the box's unit axes
  Eigen::Vector3d half_extents_m{0, 0, 0};             ///< Box: half sizes along the axes [m]
  Eigen::Vector3d a_m{0, 0, 0}, b_m{0, 0, 0};          ///< Capsule, Cylinder: axis ends [m]
  double radius_m = 0;                                 ///< Sphere, Capsule, Cylinder [m]
  std::vector<Eigen::Vector3d> vertices_m;             ///< Convex: the vertices [m]
};

/// The point of `shape` furthest along `direction` (need not be unit; a zero direction gives some point
/// of the shape). Exact for every type but HalfSpace, which is unbounded (asserts).
Eigen::Vector3d supportPoint(const ObstacleShape& shape, const Eigen::Vector3d& direction);

/// A point strictly inside the shape (for MPR's first portal), and a radius around it that holds the
/// whole shape (infinite for a half-space) [m].
Eigen::Vector3d interiorPoint(const ObstacleShape& shape);
double boundingRadius(const ObstacleShape& shape);

/// The same shape expressed in another frame: `frame` is that frame's pose in the shape's current one
/// (e.g. a car's vehiclePose() to go from the world to its vehicle frame).
ObstacleShape transformShape(const ObstacleShape& shape, const Pose& frame);

}  // namespace vehicle
