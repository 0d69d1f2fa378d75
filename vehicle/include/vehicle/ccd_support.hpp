#pragma once
// libccd glue for ObstacleShape: its support and centre functions with the signatures libccd's
// ccd_t takes, and a penetration query of a point against a shape (MPR), as the crush coupling
// will push control points out of obstacles.
#include <vehicle/obstacle_shape.hpp>

#include <ccd/ccd.h>

namespace vehicle {

/// ccd_support_fn for an `const ObstacleShape*` object (not HalfSpace).
void ccdSupport(const void* obstacle_shape, const ccd_vec3_t* direction, ccd_vec3_t* out);
/// ccd_center_fn for an `const ObstacleShape*` object.
void ccdCentre(const void* obstacle_shape, ccd_vec3_t* out);

/// How deep `point_m` is inside `shape` and which way is out (HalfSpace and Sphere in closed form, the
/// rest by libccd's MPR against a point). False when the point is outside.
bool pointPenetration(const ObstacleShape& shape, const Eigen::Vector3d& point_m, Eigen::Vector3d& out_normal,
                      double& out_depth_m);

/// How deep two shapes overlap [m] (libccd's MPR penetration depth); 0 when they do not, or when either is
/// a HalfSpace.
double overlapDepth_m(const ObstacleShape& a, const ObstacleShape& b);

}  // namespace vehicle
