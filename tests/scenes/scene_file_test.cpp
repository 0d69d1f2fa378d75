// Scene files are read strictly: every refusal names the file and the key path; --set overrides are
// checked as strictly as the file; every shipped scene parses.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <scenes/deformation_budget.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <deform/error.hpp>
#include <vehicle/material_map.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json minimalScene() {
  return json::parse(R"({
    "duration_s": 1.0,
    "physics_hz": 500,
    "vehicle": {
      "mesh": "builtin:sedan?vertices=2000",
      "mass_kg": 1500,
      "coupling": "crush",
      "start": {"speed_kmh": 20}
    },
    "obstacles": [{"type": "wall", "position_m": [5, 0], "size_m": [0.5, 4, 1.5]}]
  })");
}

// The message of the InputError parseScene throws for `document`.
std::string refusal(const json& document) {
  try {
    (void)scenes::parseScene(document, "test.json");
  } catch (const deform::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("a minimal scene takes the documented defaults", "[scenes]") {
  const scenes::SceneConfig scene = scenes::parseScene(minimalScene(), "dir/minimal.json");
  CHECK(scene.name == "minimal");
  REQUIRE(scene.vehicles.size() == 1);
  const scenes::VehicleConfig& car = scene.vehicles[0];
  CHECK(car.start.speed_kmh == 20);
  CHECK(car.deformation.preset == "balanced");
  CHECK(car.deformation.settings.control_points == 60);
  CHECK(car.drive.keys.empty());
  REQUIRE(scene.obstacles.size() == 1);
  CHECK(scene.obstacles[0].position_m.z() == Approx(0.75));  // stands on the ground
  CHECK(scene.camera.mode == scenes::CameraMode::Chase);
  CHECK(scene.outputs.width == 1280);
  CHECK(scene.outputs.height == 720);
  CHECK_FALSE(scene.outputs.video);
}

TEST_CASE("unknown keys are refused naming file and key path", "[scenes]") {
  json doc = minimalScene();
  doc["vehicle"]["start"]["sped_kmh"] = 3;
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: vehicle.start.sped_kmh: unknown key"));
  doc = minimalScene();
  doc["obstacles"][0]["hieght"] = 1;
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: obstacles[0].hieght: unknown key"));
  doc = minimalScene();
  doc["colour_grading"] = true;
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: colour_grading: unknown key"));
}

TEST_CASE("the removed visual_impulse_scale is refused with the reason", "[scenes]") {
  json doc = minimalScene();
  doc["vehicle"]["deformation"] = {{"visual_impulse_scale", 0.05}};
  CHECK_THAT(refusal(doc),
             Catch::Contains("test.json: vehicle.deformation.visual_impulse_scale: was removed"));
}

TEST_CASE("wrong types are refused naming file and key path", "[scenes]") {
  json doc = minimalScene();
  doc["vehicle"]["mass_kg"] = "heavy";
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: vehicle.mass_kg: must be a number (got a string)"));
  doc = minimalScene();
  doc["vehicle"]["deformation"] = {{"control_points", 60.5}};
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.deformation.control_points: must be an integer"));
  doc = minimalScene();
  doc["obstacles"][0]["size_m"] = {1, 2};
  CHECK_THAT(refusal(doc), Catch::Contains("obstacles[0].size_m: must be an array [x, y, z]"));
  doc = minimalScene();
  doc["outputs"] = {{"video", "yes"}};
  CHECK_THAT(refusal(doc), Catch::Contains("outputs.video: must be true or false"));
  doc = minimalScene();
  doc["vehicle"]["coupling"] = "glue";
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.coupling: unknown value 'glue'"));
}

TEST_CASE("values out of range are refused naming file and key path", "[scenes]") {
  json doc = minimalScene();
  doc["vehicle"]["mass_kg"] = -1;
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: vehicle.mass_kg: must be in"));
  doc = minimalScene();
  doc["physics_hz"] = 0;
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: physics_hz: must be in [15, 20000] (got 0)"));
  doc = minimalScene();
  doc["vehicle"]["deformation"] = {{"alpha", 40}};
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.deformation.alpha: must be in [0.5, 16] (got 40)"));
  doc = minimalScene();
  doc["vehicle"]["drive"] = {{"keys", {{{"t_s", 1}, {"throttle", 2}}}}};
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.drive.keys[0].throttle: must be in [0, 1] (got 2)"));
  doc = minimalScene();
  doc["camera"] = {{"follow", 3}};
  CHECK_THAT(refusal(doc), Catch::Contains("camera.follow: must be in [0, 0] (got 3)"));
  doc = minimalScene();
  doc["vehicle"]["deformation"] = {{"max_depenetration_mps", 0}};
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.deformation.max_depenetration_mps: must be in"));
  doc["vehicle"]["deformation"] = {{"max_depenetration_mps", 3}};
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.max_depenetration_mps == 3);
  doc["vehicle"]["deformation"] = {{"longest_contact_substep_s", -1e-3}};
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.deformation.longest_contact_substep_s: must be in"));
}

TEST_CASE("missing keys and missing files are refused naming file and key path", "[scenes]") {
  json doc = minimalScene();
  doc.erase("duration_s");
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: duration_s: missing"));
  doc = minimalScene();
  doc["vehicle"]["start"].erase("speed_kmh");
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: vehicle.start.speed_kmh: missing"));
  doc = minimalScene();
  doc["vehicle"]["mesh"] = "/no/such/car.glb";
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: vehicle.mesh: file not found: /no/such/car.glb"));
  CHECK_THROWS_WITH(scenes::loadScene("/no/such/scene.json"), Catch::Contains("/no/such/scene.json"));
  CHECK_THROWS_WITH(scenes::loadScene("no_such_scene"), Catch::Contains("wall_crash"));
}

TEST_CASE("a scene that is not valid JSON is refused naming file, line and column", "[scenes]") {
  const fs::path path = fs::temp_directory_path() / "scenes_test_broken.json";
  std::ofstream(path) << "{\n  \"duration_s\": 1,\n  \"physics_hz\" 500\n}\n";
  CHECK_THROWS_WITH(scenes::loadScene(path.string()),
                    Catch::Contains("scenes_test_broken.json: not valid JSON at line 3"));
  fs::remove(path);
}

TEST_CASE("a number too large for a double is refused naming the file or the --set key", "[scenes]") {
  // Found writing fuzz_scene: nlohmann throws out_of_range for 1e999, which escaped as an internal failure.
  CHECK_THROWS_WITH(scenes::parseSceneText(R"({"duration_s": 1e999})", "big.json", {}, "."),
                    Catch::Contains("big.json: a number too large for a double: '1e999'"));
  CHECK_THROWS_WITH(scenes::loadScene("wall_crash", {scenes::parseOverride("duration_s=-2e400")}),
                    Catch::Contains("--set duration_s: a number too large for a double: '-2e400'"));
}

TEST_CASE("a --set key or value that is not UTF-8 is refused, not an internal failure", "[scenes]") {
  // Found by fuzz_scene (regressions/scene/invalid_utf8_in_set): a bare word with the byte 0xBD became a
  // JSON string that nlohmann could not write back out (type_error 316), which ended the program.
  for (const std::string& set : {std::string("name=\xbd"),
                                 std::string("duration_s=\xbd"
                                             "2-e400"),
                                 std::string("vehicle.\xc3=1"), std::string("name=\xed\xa0\x80")})
    CHECK_THROWS_WITH(scenes::loadScene("wall_crash", {scenes::parseOverride(set)}),
                      Catch::Contains("--set: the key or the value is not valid UTF-8"));
  // Well-formed UTF-8 passes on to the key's own check.
  CHECK(
      scenes::loadScene("wall_crash", {scenes::parseOverride("name=Kraftwagen \xc3\xa4\xe2\x82\xac")}).name ==
      "Kraftwagen \xc3\xa4\xe2\x82\xac");
}

TEST_CASE("a key given twice is refused naming the file and the key's path", "[scenes]") {
  const fs::path path = fs::temp_directory_path() / "scenes_test_duplicate.json";
  const std::string head =
      R"({"duration_s": 1, "physics_hz": 500, "vehicle": {"mesh": "builtin:sedan?vertices=2000", "mass_kg": 1500, "coupling": "crush")";
  std::ofstream(path) << head << R"(, "start": {"speed_kmh": 20, "speed_kmh": 30}}})";
  CHECK_THROWS_WITH(scenes::loadScene(path.string()),
                    Catch::Contains("scenes_test_duplicate.json: vehicle.start.speed_kmh: key given twice"));
  std::ofstream(path) << head
                      << R"(}, "obstacles": [{"type": "wall", "position_m": [5, 0], "size_m": [1, 4, 1]},
                                                        {"type": "post", "type": "wall"}]})";
  CHECK_THROWS_WITH(scenes::loadScene(path.string()), Catch::Contains("obstacles[1].type: key given twice"));
  // The same key in two objects is no duplicate.
  std::ofstream(path) << head << R"(, "start": {"speed_kmh": 20}}, "obstacles": [
      {"type": "wall", "position_m": [5, 0], "size_m": [1, 4, 1]},
      {"type": "wall", "position_m": [9, 0], "size_m": [1, 4, 1]}]})";
  CHECK(scenes::loadScene(path.string()).obstacles.size() == 2);
  // In an override's value too.
  CHECK_THROWS_WITH(
      scenes::loadScene(path.string(),
                        {scenes::parseOverride(R"(vehicle.start={"speed_kmh": 1, "speed_kmh": 2})")}),
      Catch::Contains("speed_kmh: key given twice"));
  fs::remove(path);
}

TEST_CASE("overrides (--set) change any key and are checked as strictly as the file", "[scenes]") {
  json doc = minimalScene();
  scenes::applyOverride(doc, scenes::parseOverride("vehicle.start.speed_kmh=5"));
  scenes::applyOverride(doc, scenes::parseOverride("obstacles[0].size_m=[1,5,2]"));
  scenes::applyOverride(doc, scenes::parseOverride("vehicle.deformation.preset=fast"));
  const scenes::SceneConfig scene = scenes::parseScene(doc, "test.json");
  CHECK(scene.vehicles[0].start.speed_kmh == 5);
  CHECK(scene.obstacles[0].size_m.y() == 5);
  CHECK(scene.vehicles[0].deformation.settings.substeps == 2);
  CHECK(scene.vehicles[0].deformation.settings.iterations == 1);

  // One past the end appends (an extra obstacle), checked like the rest.
  doc = minimalScene();
  scenes::applyOverride(
      doc, scenes::parseOverride(
               R"(obstacles.1={"type": "post", "position_m": [9, 1], "radius_m": 0.1, "height_m": 1})"));
  CHECK(scenes::parseScene(doc, "test.json").obstacles.size() == 2);
  scenes::applyOverride(doc, scenes::parseOverride(R"(obstacles.2={"type": "post"})"));
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: obstacles[2].position_m: missing"));

  doc = minimalScene();
  scenes::applyOverride(doc, scenes::parseOverride("vehicle.start.speed=5"));
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.start.speed: unknown key"));
  doc = minimalScene();
  scenes::applyOverride(doc, scenes::parseOverride("vehicle.mass_kg=light"));
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.mass_kg: must be a number (got a string)"));
  CHECK_THROWS_WITH(scenes::parseOverride("vehicle.mass_kg"), Catch::Contains("--set"));
  CHECK_THROWS_WITH(scenes::applyOverride(doc, scenes::parseOverride("obstacles.7.x=1")),
                    Catch::Contains("--set obstacles.7.x"));
  CHECK_THROWS_WITH(scenes::applyOverride(doc, scenes::parseOverride("duration_s.x=1")),
                    Catch::Contains("--set duration_s.x"));
  CHECK_THROWS_WITH(
      scenes::loadScene("wall_crash", {scenes::parseOverride("vehicle.start.sped=1")}),
      Catch::Contains("wall_crash.json: vehicle.start.sped: unknown key") && Catch::Contains("--set"));
  // A car key under the wrong one of vehicle / vehicles says which to use.
  CHECK_THROWS_WITH(
      scenes::loadScene("car_to_car", {scenes::parseOverride("vehicle.deformation.control_points=500")}),
      Catch::Contains("--set vehicle.deformation.control_points") &&
          Catch::Contains("vehicles[0].deformation.control_points"));
  CHECK_THROWS_WITH(
      scenes::loadScene("wall_crash", {scenes::parseOverride("vehicles[0].mass_kg=900")}),
      Catch::Contains("--set vehicles[0].mass_kg") && Catch::Contains("set vehicle.mass_kg instead"));
  CHECK(scenes::loadScene("car_to_car", {scenes::parseOverride("vehicles[1].deformation.control_points=120")})
            .vehicles[1]
            .deformation.settings.control_points == 120);
}

TEST_CASE("every shipped scene parses and is found by name", "[scenes]") {
  const std::vector<std::string> names = scenes::shippedSceneNames();
  for (const char* expected : {"wall_crash", "post_bumps", "wall_slide", "rollover", "pole_side",
                               "car_to_car", "can_crush", "real_mesh"}) {
    CHECK(std::find(names.begin(), names.end(), expected) != names.end());
  }
  for (const std::string& name : names) {
    if (name == "real_mesh" && !test_support::testMeshesDir()) {
      CHECK_THROWS_WITH(scenes::loadScene(name), Catch::Contains("DEFORM_TEST_MESHES"));
      continue;
    }
    INFO(name);
    const scenes::SceneConfig scene = scenes::loadScene(name);
    CHECK(scene.name == name);
    CHECK_FALSE(scene.description.empty());
    CHECK_FALSE(scene.vehicles.empty());
  }
  const scenes::SceneConfig wall = scenes::loadScene("wall_crash");
  CHECK(wall.vehicles[0].start.speed_kmh == 56);
  CHECK(scenes::loadScene("car_to_car").vehicles.size() == 2);
}

TEST_CASE("the material map: named regions, their values, new regions, and refusals", "[scenes]") {
  // By default the built-in sedan has its map, any other mesh one material; "auto" names that default.
  const auto regionCount = [](const json& doc) {
    return scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.regions.size();
  };
  CHECK(regionCount(minimalScene()) == vehicle::sedanMaterialMap().size());
  json other = minimalScene();
  other["vehicle"]["mesh"] = "builtin:box";
  CHECK(regionCount(other) == 0);
  other["vehicle"]["deformation"]["material_map"] = "sedan";
  CHECK(regionCount(other) == vehicle::sedanMaterialMap().size());
  json uniform = minimalScene();
  uniform["vehicle"]["deformation"]["material_map"] = "uniform";
  CHECK(regionCount(uniform) == 0);
  uniform["vehicle"]["deformation"]["material_map"] = "auto";
  CHECK(regionCount(uniform) == vehicle::sedanMaterialMap().size());

  json doc = minimalScene();
  scenes::applyOverride(doc,
                        scenes::parseOverride("vehicle.deformation.regions.doors.crush_strength_Pa=3e5"));
  scenes::applyOverride(doc, scenes::parseOverride("vehicle.deformation.regions.sill.box_min=[0.3,0,0]"));
  scenes::applyOverride(doc, scenes::parseOverride("vehicle.deformation.regions.sill.box_max=[0.7,1,0.1]"));
  scenes::applyOverride(doc, scenes::parseOverride("vehicle.deformation.regions.sill.hardening=0.5"));
  const auto regions = scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.regions;
  std::vector<std::string> names;
  for (const auto& r : regions) names.push_back(r.name);
  CHECK(names == std::vector<std::string>{"bonnet", "boot", "doors", "pillars", "roof", "bumper", "sill"});
  CHECK(regions[2].get("crush_strength_Pa") == 3e5);
  CHECK(regions[4].get("crush_strength_Pa") == 6e4);  // the roof keeps the map's value
  REQUIRE(regions[6].boxes.size() == 1);
  CHECK(regions[6].boxes[0].max_m.z() == 0.1);
  CHECK(regions[6].get("hardening") == 0.5);

  json bad = minimalScene();
  bad["vehicle"]["deformation"]["material_map"] = "uniform";
  bad["vehicle"]["deformation"]["regions"]["doors"]["crush_strength_Pa"] = 1;
  CHECK_THAT(refusal(bad), Catch::Contains("vehicle.deformation.regions.doors") &&
                               Catch::Contains("material_map is uniform"));
  bad["vehicle"]["deformation"]["material_map"] = "sedan";
  bad["vehicle"]["deformation"]["regions"]["doors"]["crush_strength"] = 1;
  CHECK_THAT(refusal(bad), Catch::Contains("vehicle.deformation.regions.doors.crush_strength"));
  bad = minimalScene();
  bad["vehicle"]["deformation"]["material_map"] = "sedan";
  bad["vehicle"]["deformation"]["regions"]["roof"]["box_min"] = {0.5, 0, 0.9};
  bad["vehicle"]["deformation"]["regions"]["roof"]["box_max"] = {0.4, 1, 1};
  CHECK_THAT(refusal(bad), Catch::Contains("vehicle.deformation.regions.roof.box_max"));
  bad["vehicle"]["deformation"]["regions"]["roof"]["box_max"] = {0.6, 1, 1};
  bad["vehicle"]["deformation"]["regions"]["roof"]["crush_strength_Pa"] = -1;
  CHECK_THAT(refusal(bad), Catch::Contains("vehicle.deformation.regions.roof.crush_strength_Pa"));
  bad = minimalScene();
  bad["vehicle"]["deformation"]["material_map"] = "steel";
  CHECK_THAT(refusal(bad), Catch::Contains("vehicle.deformation.material_map"));
}

TEST_CASE("the backstop: rigid parts by default, boxes of the scene's own, or the shrunk hull", "[scenes]") {
  const auto settings = [](const json& doc) {
    return scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings;
  };
  CHECK(settings(minimalScene()).backstop == vehicle::Backstop::RigidParts);
  CHECK(settings(minimalScene()).rigid_parts.size() == 2);  // passenger cell, engine block
  json doc = minimalScene();
  doc["vehicle"]["deformation"]["rigid_parts"] =
      json::parse(R"([{"box_min": [0.3, 0.25, 0.1], "box_max": [0.7, 0.75, 0.8]}])");
  REQUIRE(settings(doc).rigid_parts.size() == 1);
  CHECK(settings(doc).rigid_parts[0].min_m.x() == 0.3);
  doc["vehicle"]["deformation"].erase("rigid_parts");
  doc["vehicle"]["deformation"]["backstop"] = "shrunk_hull";
  CHECK(settings(doc).backstop == vehicle::Backstop::ShrunkHull);

  json bad = minimalScene();
  bad["vehicle"]["deformation"]["rigid_parts"] = json::array();
  CHECK_THAT(refusal(bad), Catch::Contains("vehicle.deformation.rigid_parts"));
  bad["vehicle"]["deformation"]["rigid_parts"] =
      json::parse(R"([{"box_min": [0.3, 0, 0], "box_max": [0.2, 1, 1]}])");
  CHECK_THAT(refusal(bad), Catch::Contains("rigid_parts[0].box_max"));
  bad["vehicle"]["deformation"]["rigid_parts"] =
      json::parse(R"([{"box_min": [0.3, 0, 0], "box_max": [1.2, 1, 1]}])");
  CHECK_THAT(refusal(bad), Catch::Contains("rigid_parts[0].box_max"));
  bad = minimalScene();
  bad["vehicle"]["deformation"]["backstop"] = "airbag";
  CHECK_THAT(refusal(bad), Catch::Contains("vehicle.deformation.backstop"));
  // A key of the other backstop would be ignored: refused.
  bad = minimalScene();
  bad["vehicle"]["deformation"]["crush_allowance_m"] = 0.5;
  CHECK_THAT(refusal(bad),
             Catch::Contains("vehicle.deformation.crush_allowance_m: applies to backstop shrunk_hull"));
  bad["vehicle"]["deformation"]["backstop"] = "shrunk_hull";
  CHECK(refusal(bad) == "(accepted)");
  bad["vehicle"]["deformation"]["rigid_parts"] =
      json::parse(R"([{"box_min": [0.3, 0, 0], "box_max": [0.7, 1, 1]}])");
  CHECK_THAT(refusal(bad),
             Catch::Contains("vehicle.deformation.rigid_parts: applies to backstop rigid_parts"));
}

TEST_CASE("vehicle.deformation.skin_method takes auto, idw, mls or spline and refuses anything else",
          "[scenes]") {
  json doc = minimalScene();
  // The default, auto: the skin measured best at the car's level of detail (mls up to 60 points).
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].deformation.skin_method_auto);
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.skin_method ==
        deform::SkinMethod::mls);
  // ... and with at least 8 nearest points (or dense weights): K = 4 gets idw.
  json few = minimalScene();
  few["vehicle"]["deformation"]["k_nearest"] = 4;
  CHECK(scenes::parseScene(few, "test.json").vehicles[0].deformation.settings.skin_method ==
        deform::SkinMethod::idw);
  few["vehicle"]["deformation"]["k_nearest"] = 0;
  CHECK(scenes::parseScene(few, "test.json").vehicles[0].deformation.settings.skin_method ==
        deform::SkinMethod::mls);
  doc["vehicle"]["deformation"]["control_points"] = 120;
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.skin_method ==
        deform::SkinMethod::idw);
  doc["vehicle"]["deformation"]["skin_method"] = "auto";
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.skin_method ==
        deform::SkinMethod::idw);
  // A budget that changes the level changes auto's choice; a method named stays.
  scenes::SceneConfig config = scenes::parseScene(doc, "test.json");
  scenes::BudgetPlan plan;
  plan.cars.push_back({});
  plan.cars[0].level = "balanced";  // 60 points
  scenes::applyBudget(plan, config);
  CHECK(config.vehicles[0].deformation.settings.skin_method == deform::SkinMethod::mls);
  doc["vehicle"]["deformation"]["skin_method"] = "idw";
  config = scenes::parseScene(doc, "test.json");
  scenes::applyBudget(plan, config);
  CHECK(config.vehicles[0].deformation.settings.skin_method == deform::SkinMethod::idw);
  doc["vehicle"]["deformation"].erase("control_points");
  doc["vehicle"]["deformation"].erase("skin_method");
  scenes::applyOverride(doc, scenes::parseOverride("vehicle.deformation.skin_method=mls"));
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.skin_method ==
        deform::SkinMethod::mls);
  doc["vehicle"]["deformation"]["skin_method"] = "idw";
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.skin_method ==
        deform::SkinMethod::idw);
  doc["vehicle"]["deformation"]["skin_method"] = "rbf";
  CHECK_THAT(refusal(doc),
             Catch::Contains("test.json: vehicle.deformation.skin_method: unknown value 'rbf'"));
  doc["vehicle"]["deformation"]["skin_method"] = 2;
  CHECK_THAT(refusal(doc), Catch::Contains("vehicle.deformation.skin_method"));
  // The spline, named only (auto never takes it): dense weights, so at most 256 control points, refused
  // past that by the key's name rather than when the skin is built.
  doc["vehicle"]["deformation"]["skin_method"] = "spline";
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].deformation.settings.skin_method ==
        deform::SkinMethod::spline);
  doc["vehicle"]["deformation"]["control_points"] = 300;
  CHECK_THAT(refusal(doc),
             Catch::Contains("vehicle.deformation.skin_method: spline through every control point"));
}

TEST_CASE("collision_points sizes the chassis's rigid hull, within [8, 1000]", "[scenes]") {
  json doc = minimalScene();
  CHECK(scenes::parseScene(doc, "test.json").vehicles[0].collision_points == 64);
  doc["vehicle"]["collision_points"] = 7;
  CHECK_THAT(refusal(doc),
             Catch::Contains("test.json: vehicle.collision_points: must be in [8, 1000] (got 7)"));
  doc["vehicle"]["collision_points"] = 1.5;
  CHECK_THAT(refusal(doc), Catch::Contains("test.json: vehicle.collision_points"));
  for (long long points : {24, 200}) {
    doc["vehicle"]["collision_points"] = points;
    scenes::SceneRun run(scenes::parseScene(doc, "test.json"));
    const auto& hull = run.simulation().world().car(run.carId(0)).collisionHull();
    CHECK(hull.points_m.size() == static_cast<std::size_t>(points));
  }
}
