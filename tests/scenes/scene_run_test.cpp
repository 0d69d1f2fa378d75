// Playing scenes headless: every shipped scene runs to its end without divergence, runs are
// deterministic (same state hash), and the wall crash gives a plausible dent.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <deform/error.hpp>
#include <deform/material.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace {

// One test per shipped scene, so that `ctest -j` spreads them (traffic alone takes most of a minute under
// the sanitizers); the last test checks that the list names every shipped scene.
const std::vector<std::string> kHeadlessScenes = {"can_crush",  "car_to_car", "pole_side",
                                                  "post_bumps", "real_mesh",  "rollover",
                                                  "traffic",    "wall_crash", "wall_slide"};

void playHeadless(const std::string& name) {
  if (name == "real_mesh" && !test_support::testMeshesDir()) {
    test_support::reportSkip("real_mesh needs the shared meshes: set DEFORM_TEST_MESHES to their folder");
    return;
  }
  INFO(name);
  const auto start = std::chrono::steady_clock::now();
  scenes::SceneRun run(scenes::loadScene(name));
  run.runToEnd();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json summary = run.summary();
  std::printf(
      "[figure] %s: %llu steps in %.2f s, impact %.2f m/s, residual crush %.3f m (max %.3f), "
      "max deviation %.3f m, plastic work %.0f J, hash %s\n",
      name.c_str(), static_cast<unsigned long long>(run.steps()), seconds,
      summary["impact_speed_mps"].get<double>(), summary["residual_crush_m"].get<double>(),
      summary["max_residual_crush_m"].get<double>(), summary["max_deviation_m"].get<double>(),
      summary["energy"]["plastic_work_J"].get<double>(), summary["state_hash"].get<std::string>().c_str());
  CHECK(run.steps() == run.totalSteps());
  CHECK_FALSE(run.diverged());
  CHECK_FALSE(summary["tunnelled"].get<bool>());
  CHECK(summary["timing_ms"]["embed"].get<double>() == 0);
}

}  // namespace

TEST_CASE("every shipped scene runs headless to its end without divergence: the list is whole", "[run]") {
  CHECK(kHeadlessScenes == scenes::shippedSceneNames());
}
TEST_CASE("every shipped scene runs headless to its end without divergence: can_crush", "[run]") {
  playHeadless("can_crush");
}
TEST_CASE("every shipped scene runs headless to its end without divergence: car_to_car", "[run]") {
  playHeadless("car_to_car");
}
TEST_CASE("every shipped scene runs headless to its end without divergence: pole_side", "[run]") {
  playHeadless("pole_side");
}
TEST_CASE("every shipped scene runs headless to its end without divergence: post_bumps", "[run]") {
  playHeadless("post_bumps");
}
TEST_CASE("every shipped scene runs headless to its end without divergence: real_mesh", "[run]") {
  playHeadless("real_mesh");
}
TEST_CASE("every shipped scene runs headless to its end without divergence: rollover", "[run]") {
  playHeadless("rollover");
}
TEST_CASE("every shipped scene runs headless to its end without divergence: traffic", "[run]") {
  playHeadless("traffic");
}
TEST_CASE("every shipped scene runs headless to its end without divergence: wall_crash", "[run]") {
  playHeadless("wall_crash");
}
TEST_CASE("every shipped scene runs headless to its end without divergence: wall_slide", "[run]") {
  playHeadless("wall_slide");
}

TEST_CASE("obstacles far from every car change nothing and cost little", "[run]") {
  scenes::SceneConfig scene = scenes::loadScene("wall_crash");
  scene.duration_s = 0.6;
  const auto timed = [](const scenes::SceneConfig& config, std::string& hash) {
    const auto start = std::chrono::steady_clock::now();
    scenes::SceneRun run(config);
    run.runToEnd();
    hash = run.summary()["state_hash"].get<std::string>();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::string plain_hash, crowded_hash;
  const double plain_s = timed(scene, plain_hash);
  for (int i = 0; i < 200; ++i) {  // a forest of posts a kilometre away
    scenes::ObstacleConfig post;
    post.type = scenes::ObstacleType::Post;
    post.position_m = {1000.0 + 3.0 * (i % 20), 3.0 * (i / 20), 0.0};
    post.radius_m = 0.1;
    post.height_m = 1.0;
    scene.obstacles.push_back(post);
  }
  const double crowded_s = timed(scene, crowded_hash);
  std::printf("[figure] wall_crash 0.6 s: %.3f s alone, %.3f s with 200 far posts\n", plain_s, crowded_s);
  CHECK(crowded_hash == plain_hash);
  CHECK(crowded_s < 3.0 * plain_s + 0.2);
}

TEST_CASE("the material map acts where its region is: weaker doors let the side pole further in", "[run]") {
  // pole_side (300 points): uniform against the sedan map (doors at 2e5 Pa against 4e5), and the sedan map
  // with the doors as strong as the rest (the side pole meets no other changed region first).
  const auto deepest = [](const std::vector<std::string>& sets) {
    std::vector<scenes::Override> overrides;
    for (const auto& s : sets) overrides.push_back(scenes::parseOverride(s));
    scenes::SceneRun run(scenes::loadScene("pole_side", overrides));
    run.runToEnd();
    return run.summary()["max_residual_crush_m"].get<double>();
  };
  const double uniform_m = deepest({"vehicle.deformation.material_map=uniform"});
  const double sedan_m = deepest({});  // the built-in sedan's map is the default
  const double strong_doors_m = deepest(
      {"vehicle.deformation.material_map=sedan", "vehicle.deformation.regions.doors.crush_strength_Pa=4e5"});
  INFO("deepest dent: uniform " << uniform_m << " m, sedan map " << sedan_m << " m, its doors at 4e5 Pa "
                                << strong_doors_m << " m");
  CHECK(sedan_m > 1.1 * uniform_m);  // measured 0.199 against 0.146 m; 0.143 with the doors at 4e5 Pa
  CHECK(strong_doors_m < sedan_m);
}

TEST_CASE("a car placed inside an obstacle or another car at the start is refused, naming both", "[run]") {
  // The sedan put into the wall used to start crushed and end 1 m deformed on top of it.
  const auto refusal = [](const std::string& scene, const std::string& set) {
    try {
      scenes::SceneRun run(scenes::loadScene(scene, {scenes::parseOverride(set)}));
    } catch (const deform::InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  CHECK_THAT(refusal("wall_crash", "obstacles[0].position_m=[2.5,0]"),
             Catch::Contains("wall_crash.json: vehicle (sedan) overlaps obstacles[0] at the start by 0.19"));
  CHECK_THAT(refusal("car_to_car", "vehicles[1].start.position_m=[2,0]"),
             Catch::Contains("vehicles[0] (striking) overlaps vehicles[1] (struck)"));
  // A car denser than any solid: a wrong mass or a mesh in the wrong units (a 1500 kg drinks can spun
  // its chassis without bound). The heaviest sedan the stress suite drives (40 t) is 3,300 kg/m^3.
  CHECK_THAT(
      refusal("wall_crash", "vehicle.mesh=builtin:can"),
      Catch::Contains("wall_crash.json: vehicle.mass_kg: the bounding box of builtin:can holds 0.531 L"));
  CHECK(refusal("wall_crash", "vehicle.mass_kg=40000") == "(accepted)");
  // Touching (the wall's near face 5 mm into the bumper, within the 1 cm allowed) is not refused.
  CHECK(refusal("wall_crash", "obstacles[0].position_m=[2.695,0]") == "(accepted)");
}

TEST_CASE("a driver's input overrides the drive script until it is released", "[run]") {
  // wall_crash coasts until 0.8 s; started 10 m further back it meets the wall after 0.8 s: braking from the
  // start slows the car, the script alone does not.
  const scenes::SceneConfig config = scenes::loadScene(
      "wall_crash",
      {scenes::parseOverride("duration_s=0.6"), scenes::parseOverride("vehicle.start.position_m=[-10, 0]")});
  scenes::SceneRun scripted(config), braked(config);
  auto speed = [](const scenes::SceneRun& run) {
    return run.simulation().world().car(run.carId(0)).forwardSpeed_mps();
  };
  vehicle::DriverInput brake;
  brake.brake = 1.0;
  braked.overrideDriverInput(0, brake);
  REQUIRE(braked.driverOverride(0).has_value());
  scripted.stepUntil(0.2);
  braked.stepUntil(0.2);
  const double coasting_mps = speed(scripted), braking_mps = speed(braked);
  CHECK(coasting_mps > 15.0);  // 56 km/h, less rolling losses
  INFO("coasting " << coasting_mps << " m/s, braking " << braking_mps << " m/s");
  CHECK(braking_mps < coasting_mps - 0.5);                  // 0.2 s of full braking takes well over 0.5 m/s
  CHECK(braking_mps > coasting_mps - 0.2 * 12);             // and no more than the tyres can (1.2 g)
  CHECK_FALSE(scripted.summary()["impacted"].get<bool>());  // both measured before the wall
  CHECK(braked.simulation().world().car(braked.carId(0)).input().brake == 1.0);
  // Released: the script's input again (no brake before 0.8 s).
  braked.overrideDriverInput(0, std::nullopt);
  braked.step();
  CHECK(braked.simulation().world().car(braked.carId(0)).input().brake == 0.0);
}

TEST_CASE("Energy balance: the side pole closes, and a car struck by another counts the other's work",
          "[run][energy]") {
  const auto cars = [](const std::string& name, const std::vector<std::string>& sets) {
    std::vector<scenes::Override> overrides;
    for (const auto& s : sets) overrides.push_back(scenes::parseOverride(s));
    scenes::SceneRun run(scenes::loadScene(name, overrides));
    run.runToEnd();
    return run.summary()["cars"];
  };
  const auto fraction = [](const nlohmann::json& car) {
    const nlohmann::json& e = car["energy"];
    return e["balance_error_J"].get<double>() / e["kinetic_initial_J"].get<double>();
  };
  // pole_side as shipped (300 points): +2.0 % unexplained, a loss (+6.1 % while the shell's inertia was
  // shared twice; docs/CRASH_CALIBRATION.md, "Energy account"). At 2000 points the face contacts created
  // 5.8 kJ before they had a margin (-7.4 %).
  const nlohmann::json pole = cars("pole_side", {})[0];
  INFO("pole_side: " << pole["energy"].dump());
  CHECK(fraction(pole) > -0.02);  // not created
  CHECK(fraction(pole) < 0.05);
  CHECK(std::abs(pole["energy"]["obstacle_work_J"].get<double>()) < 1.0);  // a post stands still

  // car_to_car: each car's balance counts the work the other car's motion did on it through its body.
  // Without that term the striking car explained 29 % too little and the struck one 95 % too much
  // (energy "created"); measured with it: +4.7 % and +20.5 % (the struck car's loss is open,
  // docs/CRASH_CALIBRATION.md).
  const nlohmann::json pair = cars("car_to_car", {});
  for (const nlohmann::json& car : pair) {
    INFO(car["name"].get<std::string>() << ": " << car["energy"].dump());
    CHECK(fraction(car) > -0.02);                                            // not created
    CHECK(std::abs(car["energy"]["obstacle_work_J"].get<double>()) > 1000);  // the other car moved
  }
  CHECK(std::abs(fraction(pair[0])) < 0.05);
}

TEST_CASE("Energy balance: a drinks can of aluminium closes through its hit on a block", "[run][energy]") {
  // Through the hit and the 0.1 s after it: +3.2 %. With the sedan's steel the can's bends and hinges
  // were so stiff on its 1.7 g points that the solve never converged: its plastic work was 268 % of its
  // kinetic energy (docs/CRASH_CALIBRATION.md, "Energy account").
  scenes::SceneRun run(scenes::loadScene("can_crush", {scenes::parseOverride("duration_s=0.1")}));
  run.runToEnd();
  const nlohmann::json can = run.summary()["cars"][0];
  const nlohmann::json& e = can["energy"];
  INFO(e.dump());
  REQUIRE(can["impacted"].get<bool>());
  const double fraction = e["balance_error_J"].get<double>() / e["kinetic_initial_J"].get<double>();
  CHECK(fraction > -0.02);  // nothing created
  CHECK(fraction < 0.05);
  CHECK(e["plastic_work_J"].get<double>() > 0.5 * e["kinetic_initial_J"].get<double>());  // it dents
  CHECK(e["plastic_work_J"].get<double>() < e["kinetic_initial_J"].get<double>());
}

TEST_CASE("Energy balance: a block dropped on the can does its work on the can's body", "[run][energy]") {
  // A 6 kg block falls 0.2 m onto the can at rest. It used to meet the can's backstop, the hull shrunk
  // horizontally and full height, so the body never felt it; and a free obstacle's velocity was taken as
  // zero, so what crushed the body had done no work on it (11 J of plastic work from 0 J, "created").
  // Measured to 0.3 s: obstacle work 13.8 J, plastic 10.9 J, contact loss 3.1 J, balance -0.5 J (-3.6 %).
  scenes::SceneRun run(scenes::loadScene(
      "can_crush",
      {scenes::parseOverride("obstacles.0.position_m=[0,0,0.4]"),
       scenes::parseOverride("obstacles.0.mass_kg=6"), scenes::parseOverride("vehicle.start.speed_kmh=0"),
       scenes::parseOverride("duration_s=0.3")}));
  run.runToEnd();
  const nlohmann::json can = run.summary()["cars"][0];
  const nlohmann::json& e = can["energy"];
  INFO(e.dump());
  REQUIRE(can["impacted"].get<bool>());
  const double put_in_J = e["obstacle_work_J"].get<double>() + e["kinetic_initial_J"].get<double>();
  const double fall_J = 6.0 * 9.81 * 0.2;  // the block's fall onto the can's top, before any crush
  CHECK(e["obstacle_work_J"].get<double>() > 0.8 * fall_J);
  CHECK(e["plastic_work_J"].get<double>() > 0.5 * fall_J);  // its top caves in
  CHECK(can["crushed_volume_m3"].get<double>() > 20e-6);    // of 330 ml
  const double fraction = e["balance_error_J"].get<double>() / put_in_J;
  CHECK(fraction > -0.05);
  CHECK(fraction < 0.05);
}

TEST_CASE("Crushed volume converges in N, and the energy per crushed volume is the crush strength",
          "[run][energy]") {
  // The material absorbs sigma per cubic metre it crushes (docs/CRASH_CALIBRATION.md): the crushed volume
  // is the converged answer, however wide the level of detail spreads the dent (the pole's deepest dent
  // is 0.093 m at 60 points and 0.265 m at 500). Measured: wall 365.5 / 363.0 L, pole 114.5 / 116.8 L.
  // One material everywhere (the sedan's map would give the doors half the crush strength).
  const double crush_strength_Pa = deform::Material{}.crush_strength_Pa;
  for (const std::string name : {"wall_crash", "pole_side"}) {
    double volume_m3[2] = {0, 0};
    const std::size_t levels[2] = {60, 500};
    for (int k = 0; k < 2; ++k) {
      scenes::SceneRun run(scenes::loadScene(
          name, {scenes::parseOverride("vehicle.deformation.control_points=" + std::to_string(levels[k])),
                 scenes::parseOverride("vehicle.deformation.material_map=uniform")}));
      run.runToEnd();
      const nlohmann::json car = run.summary()["cars"][0];
      volume_m3[k] = car["crushed_volume_m3"].get<double>();
      const double plastic_J = car["energy"]["plastic_work_J"].get<double>();
      INFO(name << " at " << levels[k] << " points: crushed " << volume_m3[k] << " m^3, plastic work "
                << plastic_J << " J");
      CHECK(volume_m3[k] > 0.05);
      // The columns' share of the plastic work is sigma x volume; edges and bends fold a little more.
      CHECK(crush_strength_Pa * volume_m3[k] > 0.8 * plastic_J);
      CHECK(crush_strength_Pa * volume_m3[k] < 1.05 * plastic_J);
    }
    INFO(name << ": " << volume_m3[0] << " against " << volume_m3[1] << " m^3");
    CHECK(std::abs(volume_m3[0] / volume_m3[1] - 1) < 0.1);
  }
}

TEST_CASE("The energy an obstacle puts into the body converges in N, however the dent spreads",
          "[run][energy]") {
  // The item 3: at coarse N the pole's dent is wider and shallower (its deepest residual crush
  // 0.106 m at 60 points against 0.177 m at 500), and it absorbs the same energy. The obstacle's work on the
  // body, in the chassis's frame, with the shipped material map. Measured: wall 188.2 / 186.3 kJ, pole 40.0 /
  // 41.5 kJ at 60 / 500 points (docs/CRASH_CALIBRATION.md).
  for (const std::string name : {"wall_crash", "pole_side"}) {
    double work_J[2] = {0, 0}, deepest_m[2] = {0, 0};
    const std::size_t levels[2] = {60, 500};
    for (int k = 0; k < 2; ++k) {
      scenes::SceneRun run(scenes::loadScene(
          name, {scenes::parseOverride("vehicle.deformation.control_points=" + std::to_string(levels[k]))}));
      run.runToEnd();
      const nlohmann::json car = run.summary()["cars"][0];
      work_J[k] = car["energy"]["contact_work_J"].get<double>();
      deepest_m[k] = car["max_residual_crush_m"].get<double>();
      const double impact_J = car["energy"]["kinetic_initial_J"].get<double>();
      INFO(name << " at " << levels[k] << " points: " << work_J[k] << " J into the body of " << impact_J);
      CHECK(work_J[k] > 0.5 * impact_J);
      CHECK(work_J[k] < 1.1 * impact_J);
    }
    INFO(name << ": " << work_J[0] << " against " << work_J[1] << " J, deepest residual crush "
              << deepest_m[0] << " against " << deepest_m[1] << " m");
    CHECK(std::abs(work_J[0] / work_J[1] - 1) < 0.1);
    // The pole's coarse dent is the shallower one (0.106 against 0.177 m), while its energy agrees.
    if (name == "pole_side") CHECK(deepest_m[0] < 0.8 * deepest_m[1]);
  }
}

TEST_CASE("traffic: 30 and more cars at a junction, several dented at once, within the budget", "[run]") {
  scenes::SceneRun run(scenes::loadScene("traffic"));
  REQUIRE(run.carCount() >= 30);
  REQUIRE(run.budgetPlan());
  CHECK(run.budgetPlan()->met);
  CHECK(run.budgetPlan()->estimated_ms <= run.budgetPlan()->budget_ms);
  run.runToEnd();
  CHECK_FALSE(run.diverged());
  const nlohmann::json summary = run.summary();
  int dented = 0, impacted = 0;
  for (const nlohmann::json& car : summary["cars"]) {
    CHECK_FALSE(car["tunnelled"].get<bool>());
    impacted += car["impacted"].get<bool>();
    dented += car["max_deviation_m"].get<double>() > 0.1;
  }
  std::printf(
      "[figure] traffic: %zu cars, %d impacted, %d dented by more than 0.1 m, budget %.2f ms, "
      "estimated %.2f ms, measured %.2f ms per step\n",
      run.carCount(), impacted, dented, run.budgetPlan()->budget_ms, run.budgetPlan()->estimated_ms,
      summary["deformation_budget"]["measured_ms_per_step"].get<double>());
  CHECK(dented >= 4);
  CHECK(impacted <= 10);  // a few collisions, not a pile-up of every car
}
