// Cars out of the camera's view are not embedded (issue 12): render::sphereInView, the test that decides.
#include <catch2/catch.hpp>

#include "render/camera.hpp"

using sandbox::render::Camera;
namespace render = sandbox::render;

TEST_CASE("a sphere is in view in front of the camera and out of it behind, beside, beyond", "[render]") {
  Camera camera;
  camera.eye_m = {0, 0, 2};
  camera.target_m = {10, 0, 2};  // looking along +X
  camera.fov_y_deg = 40;
  camera.near_m = 0.1f;
  camera.far_m = 200;
  const float aspect = 16.0f / 9.0f;
  CHECK(render::sphereInView(camera, aspect, {10, 0, 2}, 1));
  CHECK_FALSE(render::sphereInView(camera, aspect, {-10, 0, 2}, 1));  // behind
  CHECK_FALSE(render::sphereInView(camera, aspect, {10, 30, 2}, 1));  // far to the left
  CHECK_FALSE(render::sphereInView(camera, aspect, {10, 0, 40}, 1));  // far above
  CHECK_FALSE(render::sphereInView(camera, aspect, {300, 0, 2}, 1));  // beyond the far plane
  // Just outside the left edge, a sphere reaching over it is in view; a smaller one is not.
  // The half-width at x = 10 is 10 tan(20 deg) * aspect = 6.47 m.
  CHECK(render::sphereInView(camera, aspect, {10, 7.5f, 2}, 1.5f));
  CHECK_FALSE(render::sphereInView(camera, aspect, {10, 7.5f, 2}, 0.5f));
}
