// The deformation budget (scene key deformation_budget_ms): more cars get coarser levels, the chosen
// levels fit the budget, the cars that crash first (along their drive scripts) and those near the camera
// are served first, an impossible budget says so, and a negative one is refused naming the key.
#include <catch2/catch.hpp>

#include <scenes/deformation_budget.hpp>
#include <scenes/scene_file.hpp>

#include <deform/error.hpp>
#include <deform/skin.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

using nlohmann::json;

namespace {

/// `cars` sedans in a row 10 m apart driving along +x at 30 km/h, with a wall ahead of the first only
/// when `wall` is set; the camera stands by the last car.
scenes::SceneConfig row(std::size_t cars, bool wall) {
  json scene = {
      {"duration_s", 1.0}, {"physics_hz", 500}, {"vehicles", json::array()}, {"obstacles", json::array()}};
  for (std::size_t i = 0; i < cars; ++i)
    scene["vehicles"].push_back(
        {{"mesh", "builtin:sedan?vertices=2000"},
         {"mass_kg", 1500},
         {"coupling", "crush"},
         {"start", {{"position_m", {0.0, 10.0 * static_cast<double>(i)}}, {"speed_kmh", 30}}}});
  if (wall)
    scene["obstacles"].push_back({{"type", "wall"}, {"position_m", {8, 0}}, {"size_m", {0.5, 4, 1.5}}});
  scene["camera"] = {{"mode", "fixed"}, {"eye_m", {0, 10.0 * static_cast<double>(cars) + 5, 3}}};
  return scenes::parseScene(scene, "row.json");
}

std::size_t levelIndex(const std::string& name) {
  const auto& levels = scenes::deformationLevels();
  for (std::size_t i = 0; i < levels.size(); ++i)
    if (levels[i].name == name) return i;
  FAIL("no level " << name);
  return 0;
}

double meanLevel(const scenes::BudgetPlan& plan) {
  double sum = 0;
  for (const scenes::BudgetChoice& c : plan.cars) sum += static_cast<double>(levelIndex(c.level));
  return sum / static_cast<double>(plan.cars.size());
}

}  // namespace

TEST_CASE("Budget: the levels cost more the finer they are, and the presets are three of them",
          "[scenes][budget]") {
  const auto& levels = scenes::deformationLevels();
  for (std::size_t i = 1; i < levels.size(); ++i) {
    CHECK(levels[i].driving_ms > levels[i - 1].driving_ms);
    CHECK(levels[i].obstacle_ms > levels[i - 1].obstacle_ms);
    CHECK(levels[i].car_ms > levels[i - 1].car_ms);
  }
  for (const char* name : {"fast", "balanced", "accurate"}) {
    const auto preset = scenes::deformationPreset(name);
    REQUIRE(preset);
    const scenes::DeformationLevel* level = scenes::deformationLevel(name);
    REQUIRE(level);
    CHECK(preset->settings.control_points == level->control_points);
    CHECK(preset->settings.substeps == level->substeps);
    CHECK(preset->settings.iterations == level->iterations);
    CHECK(preset->settings.skin_method ==
          deform::preferredSkinMethod(level->control_points, preset->settings.k_nearest));  // auto
  }
}

TEST_CASE("Budget: more cars get coarser levels, within the budget", "[scenes][budget]") {
  const double budget_ms = 1.0;
  double previous = 1e9;
  for (const std::size_t cars : {1, 4, 16, 64}) {
    const scenes::BudgetPlan plan = scenes::planDeformationBudget(row(cars, false), budget_ms);
    INFO(cars << " cars");
    REQUIRE(plan.cars.size() == cars);
    REQUIRE(plan.met);
    CHECK(plan.estimated_ms <= budget_ms + 1e-12);
    double sum = 0;
    for (const scenes::BudgetChoice& c : plan.cars) sum += c.estimated_ms;
    CHECK(sum == Approx(plan.estimated_ms));
    const double mean = meanLevel(plan);
    CHECK(mean <= previous);
    previous = mean;
  }
  CHECK(meanLevel(scenes::planDeformationBudget(row(1, false), budget_ms)) >
        meanLevel(scenes::planDeformationBudget(row(64, false), budget_ms)));
}

TEST_CASE("Budget: the car that will crash first and the one near the camera come first",
          "[scenes][budget]") {
  const scenes::SceneConfig scene = row(6, true);  // only the first car has the wall ahead
  const scenes::BudgetPlan plan = scenes::planDeformationBudget(scene, 0.6);
  REQUIRE(plan.met);
  CHECK(plan.cars[0].meets == scenes::Meets::Obstacle);
  CHECK(std::isfinite(plan.cars[0].first_contact_s));
  CHECK(plan.cars[0].priority == 0);
  CHECK(plan.cars[5].priority == 1);  // the others by their distance to the camera, by the last car
  CHECK(plan.cars[1].priority == 5);
  for (std::size_t i = 1; i < 6; ++i) {
    CHECK(plan.cars[i].meets == scenes::Meets::Nothing);
    CHECK(levelIndex(plan.cars[0].level) >= levelIndex(plan.cars[i].level));
  }
  CHECK(levelIndex(plan.cars[5].level) >= levelIndex(plan.cars[1].level));
}

TEST_CASE("Budget: one that even the coarsest levels exceed says so and keeps them", "[scenes][budget]") {
  const scenes::BudgetPlan plan = scenes::planDeformationBudget(row(10, false), 0.01);
  CHECK_FALSE(plan.met);
  for (const scenes::BudgetChoice& c : plan.cars) CHECK(c.level == scenes::deformationLevels().front().name);
  CHECK(plan.estimated_ms > 0.01);
}

TEST_CASE("Budget: a car that names the spline skin is never raised past the points that skin takes",
          "[scenes][budget]") {
  // The spline skin refuses more than 256 control points; an ample budget used to raise the car to
  // `finest` (1000 points) and the run then stopped at the skin's build.
  scenes::SceneConfig config = row(2, true);
  config.vehicles[0].deformation.skin_method_auto = false;
  config.vehicles[0].deformation.settings.skin_method = deform::SkinMethod::spline;
  const scenes::BudgetPlan plan = scenes::planDeformationBudget(config, 1e3);
  scenes::applyBudget(plan, config);
  CHECK(config.vehicles[0].deformation.settings.control_points <= deform::kSplineMostControlPoints);
  CHECK(config.vehicles[0].deformation.settings.skin_method == deform::SkinMethod::spline);
  // The other car, skin `auto`, takes the finest level the budget allows.
  CHECK(config.vehicles[1].deformation.settings.control_points ==
        scenes::deformationLevels().back().control_points);
}

TEST_CASE("Budget: a car that will crash into another never gets the coarsest level", "[scenes][budget]") {
  // Two cars head-on and a third driving away: at 2 substeps x 1 iteration two bodies in contact do not
  // hold apart at 120 Hz (docs/CRASH_CALIBRATION.md), so however small the budget, the pair starts one
  // level up and the budget says it is not met; the third may still take the coarsest.
  json scene = {{"duration_s", 2.0}, {"physics_hz", 120}, {"vehicles", json::array()}};
  const double x[3] = {0, 9, 40}, heading[3] = {0, 180, 0};
  for (int i = 0; i < 3; ++i)
    scene["vehicles"].push_back(
        {{"mesh", "builtin:sedan?vertices=2000"},
         {"mass_kg", 1500},
         {"coupling", "crush"},
         {"start", {{"position_m", {x[i], 0.0}}, {"heading_deg", heading[i]}, {"speed_kmh", 30}}}});
  const scenes::BudgetPlan plan = scenes::planDeformationBudget(scenes::parseScene(scene, "pair.json"), 0.0);
  CHECK_FALSE(plan.met);
  REQUIRE(plan.cars.size() == 3);
  for (int i = 0; i < 2; ++i) {
    CHECK(plan.cars[static_cast<std::size_t>(i)].meets == scenes::Meets::Car);
    CHECK(levelIndex(plan.cars[static_cast<std::size_t>(i)].level) == 1);
  }
  CHECK(plan.cars[2].meets == scenes::Meets::Nothing);
  CHECK(levelIndex(plan.cars[2].level) == 0);
}

TEST_CASE("Budget: the scene key is applied to every car, and a negative budget is refused",
          "[scenes][budget]") {
  json scene = {{"duration_s", 1.0},
                {"physics_hz", 500},
                {"deformation_budget_ms", -1},
                {"vehicle",
                 {{"mesh", "builtin:sedan?vertices=2000"},
                  {"mass_kg", 1500},
                  {"coupling", "crush"},
                  {"start", {{"speed_kmh", 20}}}}}};
  CHECK_THROWS_WITH(scenes::parseScene(scene, "budget.json"),
                    Catch::Contains("budget.json") && Catch::Contains("deformation_budget_ms"));
  scene["deformation_budget_ms"] = 0.2;
  scenes::SceneConfig config = scenes::parseScene(scene, "budget.json");
  REQUIRE(config.deformation_budget_ms);
  const scenes::BudgetPlan plan = scenes::planDeformationBudget(config, *config.deformation_budget_ms);
  scenes::applyBudget(plan, config);
  const scenes::DeformationLevel* level = scenes::deformationLevel(plan.cars[0].level);
  REQUIRE(level);
  CHECK(config.vehicles[0].deformation.settings.control_points == level->control_points);
  CHECK(config.vehicles[0].deformation.preset == level->name);
}

TEST_CASE("Budget: a fine car against an obstacle is charged the substeps the contact cap adds",
          "[scenes][budget]") {
  // The obstacle costs were measured at 500 Hz (2 ms steps: 4 substeps of 0.5 ms, the cap's own length).
  // At 120 Hz a level of 250 points or more takes ceil(8.33 / 0.5) = 17 substeps in contact, not 4.
  const vehicle::DeformationSettings car;
  const scenes::DeformationLevel& fast = *scenes::deformationLevel("fast");
  const scenes::DeformationLevel& accurate = *scenes::deformationLevel("accurate");
  CHECK(scenes::contactCostScale(accurate, car, 1.0 / 500) == 1.0);
  CHECK(scenes::contactCostScale(accurate, car, 1.0 / 120) == Approx(17.0 / 4.0));
  CHECK(scenes::contactCostScale(fast, car, 1.0 / 120) == 1.0);  // below 250 points: no cap
  vehicle::DeformationSettings own = car;
  own.longest_contact_substep_s = 1e-3;  // a scene's own cap applies to every level
  CHECK(scenes::contactCostScale(fast, own, 1.0 / 120) == Approx(9.0 / 2.0));
  // The plan charges it: one car driving into a wall at 120 Hz against the same car at 500 Hz.
  json scene = {{"duration_s", 1.0},
                {"physics_hz", 500},
                {"vehicles",
                 {{{"mesh", "builtin:sedan?vertices=2000"},
                   {"mass_kg", 1500},
                   {"coupling", "crush"},
                   {"start", {{"position_m", {0.0, 0.0}}, {"speed_kmh", 30}}}}}},
                {"obstacles", {{{"type", "wall"}, {"position_m", {8, 0}}, {"size_m", {0.5, 4, 1.5}}}}}};
  const scenes::BudgetPlan at500 = scenes::planDeformationBudget(scenes::parseScene(scene, "w.json"), 100);
  scene["physics_hz"] = 120;
  const scenes::BudgetPlan at120 = scenes::planDeformationBudget(scenes::parseScene(scene, "w.json"), 100);
  REQUIRE(at500.cars[0].meets == scenes::Meets::Obstacle);
  REQUIRE(at500.cars[0].level == "finest");
  REQUIRE(at120.cars[0].level == "finest");
  CHECK(at120.cars[0].estimated_ms == Approx(at500.cars[0].estimated_ms * std::ceil(500.0 / 120.0 * 4) / 4));
}

TEST_CASE("Budget: who meets what is found along the drive scripts, not on straight lines",
          "[scenes][budget]") {
  // Three cars at 30 km/h, 20 m apart across: the first brakes hard before the wall ahead of it; the
  // second turns left into a post 9 m off its straight line; the third drives on past the wall's end.
  json scene = {{"duration_s", 4.0}, {"physics_hz", 120}, {"vehicles", json::array()}};
  const json drives[3] = {
      {{"keys", {{{"t_s", 0}, {"brake", 1}}}}},
      {{"keys", {{{"t_s", 0}, {"target_speed_kmh", 30}}, {{"t_s", 0.5}, {"steering", 0.6}}}}},
      {{"keys", {{{"t_s", 0}, {"target_speed_kmh", 30}}}}}};
  for (int i = 0; i < 3; ++i)
    scene["vehicles"].push_back({{"mesh", "builtin:sedan?vertices=2000"},
                                 {"mass_kg", 1500},
                                 {"coupling", "crush"},
                                 {"start", {{"position_m", {0.0, -20.0 * i}}, {"speed_kmh", 30}}},
                                 {"drive", drives[i]}});
  scene["obstacles"] = {{{"type", "wall"}, {"position_m", {14, 0}}, {"size_m", {0.5, 4, 1.5}}},
                        {{"type", "post"}, {"position_m", {9.5, -11}}, {"radius_m", 0.3}, {"height_m", 1}}};
  const scenes::SceneConfig config = scenes::parseScene(scene, "routes.json");
  const std::vector<scenes::FirstContact> first =
      scenes::rehearseFirstContacts(config, scenes::loadVehicleModels(config), 1, config.duration_s);
  REQUIRE(first.size() == 3);
  CHECK(first[0].meets == scenes::Meets::Nothing);  // stopped in 4.5 m, the wall 11.6 m ahead
  CHECK(first[1].meets == scenes::Meets::Obstacle);
  CHECK(first[1].time_s > 0.5);
  CHECK(first[1].time_s < 3.0);
  CHECK(first[2].meets == scenes::Meets::Nothing);
  CHECK_FALSE(std::isfinite(first[2].time_s));
  // The plan takes them from there: the turning car comes first.
  const scenes::BudgetPlan plan = scenes::planDeformationBudget(config, 1.0);
  CHECK(plan.cars[1].meets == scenes::Meets::Obstacle);
  CHECK(plan.cars[1].first_contact_s == first[1].time_s);
  CHECK(plan.cars[1].priority == 0);
}
