// front_profile: the front-most x per slice across the width, and its spread over the middle of it.
#include <figures/dented_car.hpp>
#include <figures/front_profile.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

TEST_CASE("front profile: a flat front has no spread, a pointed nose spreads by its slope",
          "[figures][front_profile]") {
  deform::Aabb box;
  box.min_m = {-2, -1, 0};
  box.max_m = {2, 1, 1};
  // Vertices every 1 cm across the width at the front (x = 2), and a point far behind in every slice.
  std::vector<Eigen::Vector3f> flat, nose;
  for (int i = 0; i <= 200; ++i) {
    const float y = -1.0f + 0.01f * static_cast<float>(i);
    flat.push_back({2.0f, y, 0.5f});
    flat.push_back({-2.0f, y, 0.5f});
    nose.push_back({2.0f - 0.5f * std::abs(y), y, 0.5f});  // 0.5 m back per metre out from the middle
  }
  const auto flat_profile = sandbox::figures::frontProfile(flat, box);
  REQUIRE(flat_profile.y_m.size() == 20);  // 2 m in 0.1 m slices
  CHECK(flat_profile.variation_m == Approx(0).margin(1e-6));
  for (double x : flat_profile.front_x_m) CHECK(x == Approx(2.0));
  // Middle 80 %: slice centres within 0.8 m of the axis, the outermost at |y| = 0.75 m, whose front-most
  // vertex sits at |y| = 0.70-0.71 m (0.35-0.355 m back); the middle slice reaches x = 2 (y = 0).
  const auto nose_profile = sandbox::figures::frontProfile(nose, box);
  CHECK(nose_profile.variation_m == Approx(0.35).margin(0.006));
}

TEST_CASE("front profile after the 56 km/h wall crash: mls within the 5 cm asked, idw measured",
          "[figures][front_profile]") {
  // The target for the crushed front: the front-most vertex across the middle 80 % of the width
  // varies by 5 cm or less once the car is at rest. The car before the crash varies by 6.3 cm (its
  // rounded nose). Measured: mls 1.7-1.8 cm, idw 8.1 cm (its lobes between the control points: the
  // default skin does not meet the target yet).
  scenes::SceneRun run(scenes::loadScene("wall_crash", {}));
  run.runToEnd();
  const auto idw = sandbox::figures::dentCar(run, deform::SkinMethod::idw);
  const auto mls = sandbox::figures::dentCar(run, deform::SkinMethod::mls);
  const deform::Aabb box = deform::boundingBox(idw.model.body);
  const double idw_m = sandbox::figures::frontProfile(idw.dented.positions_m, box).variation_m;
  const double mls_m = sandbox::figures::frontProfile(mls.dented.positions_m, box).variation_m;
  const double rest_m = sandbox::figures::frontProfile(idw.model.body.positions_m, box).variation_m;
  const auto spline = sandbox::figures::dentCar(run, deform::SkinMethod::spline);
  const double spline_m = sandbox::figures::frontProfile(spline.dented.positions_m, box).variation_m;
  std::printf(
      "[figure] front profile after wall_crash: idw %.4f m, mls %.4f m, spline %.4f m, at rest %.4f m\n",
      idw_m, mls_m, spline_m, rest_m);
  CHECK(mls_m <= 0.05);
  CHECK(spline_m <= 0.05);
  CHECK(mls_m < idw_m);
  CHECK(rest_m > 0.05);  // the measure sees a rounded nose: a flat front is the crash's doing
}
