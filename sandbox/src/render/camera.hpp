#pragma once
// A pinhole camera (look-at plus vertical field of view) and the placements the sandbox uses: framing
// a bounding box from a named direction, a chase camera behind and above a moving car, a fixed side
// camera. World frame: Z up, X forward, Y left, metres (DESIGN.md section 2).
#include <deform/mesh.hpp>

#include <Eigen/Geometry>
#include <string>

namespace sandbox::render {

struct Camera {
  Eigen::Vector3f eye_m{-8, 4, 3};       ///< camera position [m]
  Eigen::Vector3f target_m{0, 0, 0.7f};  ///< point looked at [m]
  Eigen::Vector3f up{0, 0, 1};           ///< roughly up in the picture (need not be orthogonal to the view)
  float fov_y_deg = 35.0f;               ///< vertical field of view [degrees]
  float near_m = 0.1f;                   ///< near clipping distance [m]
  float far_m = 500.0f;                  ///< far clipping distance [m]

  /// World -> camera (OpenGL convention: camera looks down its -Z).
  Eigen::Matrix4f view() const;
  /// Camera -> clip space for a picture of width/height `aspect`.
  Eigen::Matrix4f projection(float aspect) const;
};

/// Pixel (x right, y down from the top-left corner, pixel centres at +0.5) where `point_m` appears in a
/// width x height picture, and its depth in front of the camera [m] (negative: behind the camera).
Eigen::Vector3f projectToPixel(const Camera& camera, const Eigen::Vector3f& point_m, int width, int height);

/// Whether any of the sphere at `centre_m` with `radius_m` may be in the picture (width / height
/// `aspect`): false only when it lies wholly outside one plane of the view frustum (near and far too).
bool sphereInView(const Camera& camera, float aspect, const Eigen::Vector3f& centre_m, float radius_m);

/// Camera looking along `view_direction` (from the eye towards the box) at the centre of `box`, moved
/// back just far enough that all eight corners fit with `margin` (fraction of the picture kept free on
/// each side). Near and far planes are set from the distance.
Camera fitCamera(const deform::Aabb& box, const Eigen::Vector3f& view_direction, float aspect,
                 float fov_y_deg = 35.0f, float margin = 0.08f);

/// The named views of `sandbox mesh render`: "side" (from the car's left, slightly above), "front",
/// "chase" (behind and above), "top" (straight down, front of the car at the top of the picture) and
/// "quarter" (front three-quarter view from above, the classic car picture). Throws deform::InputError
/// naming --camera for anything else.
Camera presetCamera(const std::string& name, const deform::Aabb& box, float aspect);

/// Chase camera for a moving car: `distance_m` behind the car along its heading (yaw only, so the
/// picture does not roll with the body), `height_m` above its centre, looking at a point a little
/// ahead of the car. `car_pose` maps the vehicle frame to the world.
Camera chaseCamera(const Eigen::Isometry3d& car_pose, double distance_m = 9.0, double height_m = 3.0);

/// Fixed camera at the side of a straight track: at `eye_m`, always looking at the car (`target_m`).
Camera sideCamera(const Eigen::Vector3d& eye_m, const Eigen::Vector3d& target_m, float fov_y_deg = 35.0f);

}  // namespace sandbox::render
