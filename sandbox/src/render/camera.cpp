#include "render/camera.hpp"

#include <deform/error.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace sandbox::render {
namespace {

float radians(float degrees) {
  return degrees * std::numbers::pi_v<float> / 180.0f;
}

// Unit vector that points along `azimuth_deg` (0 = +X, 90 = +Y) and `elevation_deg` below the horizon:
// the direction a camera looks when it stands there and looks at the origin.
Eigen::Vector3f lookingFrom(float azimuth_deg, float elevation_deg) {
  const float a = radians(azimuth_deg), e = radians(elevation_deg);
  // The eye stands at (cos a cos e, sin a cos e, sin e); the view direction points back to the origin.
  return -Eigen::Vector3f(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e));
}

}  // namespace

Eigen::Matrix4f Camera::view() const {
  const Eigen::Vector3f forward = (target_m - eye_m).normalized();
  Eigen::Vector3f right = forward.cross(up);
  // Looking straight along `up`: any perpendicular will do.
  if (right.squaredNorm() < 1e-12f) right = forward.cross(Eigen::Vector3f::UnitX());
  right.normalize();
  const Eigen::Vector3f true_up = right.cross(forward);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = right.transpose();
  m.block<1, 3>(1, 0) = true_up.transpose();
  m.block<1, 3>(2, 0) = -forward.transpose();
  m(0, 3) = -right.dot(eye_m);
  m(1, 3) = -true_up.dot(eye_m);
  m(2, 3) = forward.dot(eye_m);
  return m;
}

Eigen::Matrix4f Camera::projection(float aspect) const {
  const float f = 1.0f / std::tan(radians(fov_y_deg) / 2.0f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (far_m + near_m) / (near_m - far_m);
  m(2, 3) = 2.0f * far_m * near_m / (near_m - far_m);
  m(3, 2) = -1.0f;
  return m;
}

bool sphereInView(const Camera& camera, float aspect, const Eigen::Vector3f& centre_m, float radius_m) {
  // The frustum's planes from the rows of the clip matrix (Gribb and Hartmann, 2001): a point is inside
  // where w +- x, w +- y and w +- z are all >= 0.
  const Eigen::Matrix4f clip = camera.projection(aspect) * camera.view();
  const Eigen::Vector4f p = centre_m.homogeneous();
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {1.0f, -1.0f}) {
      const Eigen::Vector4f plane = clip.row(3) + sign * clip.row(axis);
      const float length = plane.head<3>().norm();
      if (!(length > 0)) continue;
      if (plane.dot(p) / length < -radius_m) return false;
    }
  return true;
}

Eigen::Vector3f projectToPixel(const Camera& camera, const Eigen::Vector3f& point_m, int width, int height) {
  const Eigen::Vector4f eye = camera.view() * point_m.homogeneous();
  const Eigen::Vector4f clip =
      camera.projection(static_cast<float>(width) / static_cast<float>(height)) * eye;
  const float x_ndc = clip.x() / clip.w(), y_ndc = clip.y() / clip.w();
  return {(x_ndc * 0.5f + 0.5f) * static_cast<float>(width),
          (0.5f - y_ndc * 0.5f) * static_cast<float>(height), -eye.z()};
}

Camera fitCamera(const deform::Aabb& box, const Eigen::Vector3f& view_direction, float aspect,
                 float fov_y_deg, float margin) {
  Camera camera;
  camera.fov_y_deg = fov_y_deg;
  const Eigen::Vector3f centre = ((box.min_m + box.max_m) * 0.5).cast<float>();
  const Eigen::Vector3f forward = view_direction.normalized();
  camera.up = std::abs(forward.z()) > 0.99f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitZ();
  const Eigen::Vector3f right = forward.cross(camera.up).normalized();
  const Eigen::Vector3f true_up = right.cross(forward);
  const float tan_y = std::tan(radians(fov_y_deg) / 2.0f) * (1.0f - 2.0f * margin);
  const float tan_x = std::tan(radians(fov_y_deg) / 2.0f) * aspect * (1.0f - 2.0f * margin);
  // A corner at offset (x, y, z) from the centre (camera axes, z towards the camera's far side) is inside
  // the frustum of an eye `d` behind the centre when |x| <= tan_x (d + z) and |y| <= tan_y (d + z).
  float distance = 0.0f, farthest = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? box.max_m.x() : box.min_m.x(),
                            (corner & 2) ? box.max_m.y() : box.min_m.y(),
                            (corner & 4) ? box.max_m.z() : box.min_m.z());
    const Eigen::Vector3f offset = p.cast<float>() - centre;
    const float z = offset.dot(forward);
    distance = std::max(
        {distance, std::abs(offset.dot(right)) / tan_x - z, std::abs(offset.dot(true_up)) / tan_y - z});
    farthest = std::max(farthest, z);
  }
  const float radius = static_cast<float>(box.diagonal_m()) * 0.5f;
  distance = std::max(distance, radius * 1e-3f + 1e-4f);
  camera.target_m = centre;
  camera.eye_m = centre - forward * distance;
  camera.near_m = std::max(1e-4f, (distance - radius) * 0.5f);
  // Far enough for the ground's horizon fade (see Environment) behind the object.
  camera.far_m = distance + farthest + 60.0f * std::max(radius, 0.05f);
  return camera;
}

Camera presetCamera(const std::string& name, const deform::Aabb& box, float aspect) {
  if (name == "side") return fitCamera(box, lookingFrom(90.0f, 8.0f), aspect);
  if (name == "front") return fitCamera(box, lookingFrom(0.0f, 10.0f), aspect);
  if (name == "chase") return fitCamera(box, lookingFrom(180.0f, 22.0f), aspect);
  if (name == "top") return fitCamera(box, Eigen::Vector3f(0, 0, -1), aspect);
  if (name == "quarter") return fitCamera(box, lookingFrom(35.0f, 18.0f), aspect);
  throw deform::InputError("--camera: unknown view '" + name + "' (side, chase, front, top or quarter)");
}

Camera chaseCamera(const Eigen::Isometry3d& car_pose, double distance_m, double height_m) {
  const Eigen::Vector3d centre = car_pose.translation();
  Eigen::Vector3d heading = car_pose.linear().col(0);
  heading.z() = 0.0;
  if (heading.squaredNorm() < 1e-12) heading = Eigen::Vector3d::UnitX();  // pointing straight up or down
  heading.normalize();
  Camera camera;
  camera.eye_m = (centre - heading * distance_m + Eigen::Vector3d(0, 0, height_m)).cast<float>();
  camera.target_m = (centre + heading * (0.25 * distance_m)).cast<float>();
  camera.near_m = 0.1f;
  camera.far_m = 1000.0f;
  return camera;
}

Camera sideCamera(const Eigen::Vector3d& eye_m, const Eigen::Vector3d& target_m, float fov_y_deg) {
  Camera camera;
  camera.eye_m = eye_m.cast<float>();
  camera.target_m = target_m.cast<float>();
  camera.fov_y_deg = fov_y_deg;
  camera.near_m = 0.1f;
  camera.far_m = 1000.0f;
  return camera;
}

}  // namespace sandbox::render
