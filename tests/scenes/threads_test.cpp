// Threads (issue 12; vehicle::Simulation::setThreads): the cars' deformation steps run in parallel, and
// the state is bit for bit the same on any thread count, with cars alone, against a wall and against
// each other.
#include <catch2/catch.hpp>

#include <deform/error.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <string>

namespace {

std::string hashOn(scenes::SceneConfig scene, int threads) {
  scene.threads = threads;
  scenes::SceneRun run(scene);
  run.runToEnd();
  CHECK_FALSE(run.diverged());
  CHECK(run.simulation().threads() == threads);
  return scenes::hashHex(run.stateHash());
}

// Six cars: two drive into a wall, two into each other, two cruise alone.
const char* kMixedScene = R"({
  "duration_s": 0.8, "physics_hz": 240,
  "vehicles": [
    {"name": "walled_a", "mesh": "builtin:sedan?vertices=2000", "mass_kg": 1500, "coupling": "crush",
     "start": {"position_m": [0, 0], "heading_deg": 0, "speed_kmh": 40}},
    {"name": "walled_b", "mesh": "builtin:sedan?vertices=2000", "mass_kg": 1500, "coupling": "crush",
     "start": {"position_m": [0, 6], "heading_deg": 0, "speed_kmh": 30}},
    {"name": "striking", "mesh": "builtin:sedan?vertices=2000", "mass_kg": 1500, "coupling": "crush",
     "start": {"position_m": [0, 20], "heading_deg": 0, "speed_kmh": 40}},
    {"name": "struck", "mesh": "builtin:sedan?vertices=2000", "mass_kg": 1400, "coupling": "crush",
     "start": {"position_m": [9.5, 20], "heading_deg": 180, "speed_kmh": 20}},
    {"name": "alone_a", "mesh": "builtin:sedan?vertices=2000", "mass_kg": 1500, "coupling": "crush",
     "start": {"position_m": [0, 40], "heading_deg": 0, "speed_kmh": 50}, "drive": {"target_speed_kmh": 50}},
    {"name": "alone_b", "mesh": "builtin:sedan?vertices=2000", "mass_kg": 1200, "coupling": "crush",
     "start": {"position_m": [0, 50], "heading_deg": 0, "speed_kmh": 30}, "drive": {"target_speed_kmh": 40}}
  ],
  "obstacles": [{"type": "wall", "position_m": [5.5, 3], "size_m": [0.6, 12, 1.6]}]
})";

}  // namespace

TEST_CASE("the state hash is the same on 1, 2 and 3 threads", "[run][threads]") {
  const scenes::SceneConfig scene = scenes::parseSceneText(kMixedScene, "mixed.json", {}, ".");
  const std::string one = hashOn(scene, 1);
  CHECK(hashOn(scene, 2) == one);
  CHECK(hashOn(scene, 3) == one);
  // The run did crash: the walled and the colliding cars are dented (else the test shows little).
  scenes::SceneConfig check = scene;
  check.threads = 2;
  scenes::SceneRun run(check);
  run.runToEnd();
  const nlohmann::json summary = run.summary();
  for (int car : {0, 1, 2, 3}) {
    INFO(car);
    CHECK(summary["cars"][car]["impacted"].get<bool>());
  }
  CHECK_FALSE(summary["cars"][4]["impacted"].get<bool>());
}

TEST_CASE("the shipped car-to-car crash has the same hash on 1 and 2 threads", "[run][threads]") {
  scenes::SceneConfig scene = scenes::loadScene("car_to_car");
  scene.duration_s = 1.0;
  CHECK(hashOn(scene, 1) == hashOn(scene, 2));
}

TEST_CASE("zero or negative threads are refused, naming the key", "[run][threads]") {
  CHECK_THROWS_WITH(scenes::parseSceneText(R"({"duration_s": 1, "physics_hz": 60, "threads": 0,
                      "vehicle": {"mesh": "builtin:box", "mass_kg": 100, "coupling": "crush", "start": {"speed_kmh": 0}}})",
                                           "t.json", {}, "."),
                    Catch::Contains("t.json: threads: must be in [1, 1024]"));
  CHECK_THROWS_WITH(scenes::parseSceneText(R"({"duration_s": 1, "physics_hz": 60, "threads": -1,
                      "vehicle": {"mesh": "builtin:box", "mass_kg": 100, "coupling": "crush", "start": {"speed_kmh": 0}}})",
                                           "t.json", {}, "."),
                    Catch::Contains("threads"));
  vehicle::Simulation sim;
  CHECK_THROWS_AS(sim.setThreads(0), deform::InputError);
  CHECK_THROWS_WITH(sim.setThreads(-3), Catch::Contains("threads: must be >= 1"));
}

TEST_CASE("the threads key does not change the settings a state file is checked against", "[run][threads]") {
  const char* base = R"({"duration_s": 1, "physics_hz": 60,
                      "vehicle": {"mesh": "builtin:box", "mass_kg": 100, "coupling": "crush", "start": {"speed_kmh": 0}})";
  const std::string plain = std::string(base) + "}";
  const std::string threaded = std::string(base) + R"(, "threads": 2})";
  CHECK(scenes::parseSceneText(plain, "t.json", {}, ".").settings_hash ==
        scenes::parseSceneText(threaded, "t.json", {}, ".").settings_hash);
}
