// The crush of the car's own surface: the crash test's six stations on the render mesh, against the
// render mesh at rest (scenes::surfaceCrush), and the wall crash measured so at two levels of detail.
#include <catch2/catch.hpp>

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>
#include <scenes/surface_crush.hpp>

#include <deform/builtin_meshes.hpp>
#include <deform/error.hpp>

#include <cmath>

TEST_CASE("surface crush: a box's front pushed back reads the push at every station, none elsewhere",
          "[scenes][surface_crush]") {
  // A 4 x 2 x 1 m box centred on the origin: its front (x = 2) pushed back 0.25 m where y > -0.5 (the
  // right quarter of the width stays), its back left alone.
  const deform::Mesh box = deform::makeBox({4, 2, 1}, 2000);
  std::vector<Eigen::Vector3f> now = box.positions_m;
  for (auto& p : now)
    if (p.x() > 1.999f) p.x() -= p.y() > -0.5f ? 0.25f : 0.0f;
  const vehicle::CrushStations front = scenes::surfaceCrush(box, now, {1, 0, 0});
  REQUIRE(front.profile_m.size() == 6);
  // Stations at y = -1 + (j + 0.5) / 3: the first (y = -0.83) in the part left alone; the second
  // (y = -0.5) on the step's edge, where the mesh's triangles slope; the other four pushed.
  CHECK(front.profile_m[0] == Approx(0).margin(1e-6));
  for (std::size_t j = 2; j < 6; ++j) CHECK(front.profile_m[j] == Approx(0.25).margin(1e-6));
  CHECK(front.max_m == Approx(0.25).margin(1e-6));
  CHECK(front.height_m >= -0.5);
  CHECK(front.height_m <= 0.5);
  // Seen from behind, nothing moved.
  const vehicle::CrushStations back = scenes::surfaceCrush(box, now, {-1, 0, 0});
  CHECK(back.mean_m == Approx(0).margin(1e-6));
  // One position per vertex, or a clear refusal.
  now.pop_back();
  CHECK_THROWS_AS(scenes::surfaceCrush(box, now, {1, 0, 0}), deform::InputError);
}

TEST_CASE("surface crush: the 56 km/h wall crash crushes the car's surface alike at 60 and 500 points",
          "[scenes][surface_crush]") {
  // The test of convergence: within 10 %. The render mesh at rest is the same at every level of
  // detail; the control surface is not (a 60-point hull cuts the front corners), which is why the
  // control surface's own six stations read 0.371 against 0.409 m (docs/CRASH_CALIBRATION.md).
  // Measured: 0.409 m at 60 points, 0.408 m at 500.
  auto crush = [](int points) {
    scenes::SceneRun run(scenes::loadScene(
        "wall_crash",
        {scenes::parseOverride("vehicle.deformation.control_points=" + std::to_string(points))}));
    run.runToEnd();
    scenes::SkinCache skins;
    const vehicle::CrushStations surface = run.surfaceCrush(0, skins);
    CHECK(surface.profile_m.size() == 6);
    return surface.mean_m;
  };
  const double coarse_m = crush(60), fine_m = crush(500);
  CHECK(coarse_m > 0.3);  // about half a metre, as the barrier tests
  CHECK(coarse_m < 0.6);
  CHECK(coarse_m == Approx(fine_m).epsilon(0.10));
}
