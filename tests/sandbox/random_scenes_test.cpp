// The random crash scenes of `sandbox stress --random` (stress/random_scenes.hpp), without running them:
// the same scene from the same seed and index, every one valid for the scene reader and written out
// exactly, and the campaign covering what it claims to.
#include <stress/footprint.hpp>
#include <stress/random_scenes.hpp>

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <catch2/catch.hpp>

#include <set>

namespace {

constexpr std::size_t kScenesPerSeed = 100;
const uint64_t kSeeds[] = {1, 7, 90210};

}  // namespace

TEST_CASE("random scenes: the same seed and index give the same scene, another seed another", "[random]") {
  for (const uint64_t seed : kSeeds) {
    for (std::size_t i = 0; i < kScenesPerSeed; ++i) {
      INFO("seed " << seed << ", scene " << i);
      CHECK(sandbox::randomScene(seed, i).document == sandbox::randomScene(seed, i).document);
    }
  }
  CHECK(sandbox::randomScene(1, 0).document != sandbox::randomScene(2, 0).document);
  CHECK(sandbox::randomScene(1, 0).document != sandbox::randomScene(1, 1).document);
}

TEST_CASE("random scenes: every one passes the scene reader, and its file reads back as the same scene",
          "[random]") {
  for (const uint64_t seed : kSeeds) {
    for (std::size_t i = 0; i < kScenesPerSeed; ++i) {
      const sandbox::RandomScene scene = sandbox::randomScene(seed, i);
      INFO(scene.document.dump());
      const std::string text = scene.document.dump(2);
      CHECK(nlohmann::json::parse(text) == scene.document);
      CHECK_NOTHROW(scenes::parseSceneText(text, scene.name + ".json", {}, "."));
    }
  }
}

TEST_CASE("random scenes: no car overlaps anything at the start (SceneRun builds every one)", "[random]") {
  // Building the world loads the meshes and builds each car's control mesh: 40 scenes, not 300.
  for (std::size_t i = 0; i < 40; ++i) {
    const sandbox::RandomScene scene = sandbox::randomScene(kSeeds[0], i);
    INFO(scene.document.dump());
    CHECK_NOTHROW(scenes::SceneRun(scenes::parseScene(scene.document, scene.name + ".json")));
  }
}

TEST_CASE("random scenes: they cover every obstacle type, preset, coupling, 1-3 cars, 0-250 km/h, 60-2000 Hz",
          "[random]") {
  std::set<std::string> obstacle_types, presets, couplings;
  std::set<std::size_t> car_counts;
  double slowest_kmh = 1e9, fastest_kmh = 0, lowest_hz = 1e9, highest_hz = 0;
  std::size_t car_to_car = 0, with_drive = 0;
  for (std::size_t i = 0; i < 300; ++i) {
    const scenes::SceneConfig scene =
        scenes::parseScene(sandbox::randomScene(kSeeds[0], i).document, "random.json");
    car_counts.insert(scene.vehicles.size());
    lowest_hz = std::min(lowest_hz, scene.physics_hz);
    highest_hz = std::max(highest_hz, scene.physics_hz);
    for (const scenes::VehicleConfig& v : scene.vehicles) {
      presets.insert(v.deformation.preset);
      couplings.insert(v.deformation.settings.coupling == vehicle::Coupling::Crush ? "crush" : "visual");
      slowest_kmh = std::min(slowest_kmh, v.start.speed_kmh);
      fastest_kmh = std::max(fastest_kmh, v.start.speed_kmh);
      CHECK(v.mass_kg >= 800);
      CHECK(v.mass_kg <= 6000);
      with_drive += v.drive.keys.empty() ? 0 : 1;
    }
    for (const scenes::ObstacleConfig& o : scene.obstacles)
      obstacle_types.insert(std::to_string(static_cast<int>(o.type)));
    car_to_car += scene.obstacles.size() < scene.vehicles.size() ? 1 : 0;
  }
  CHECK(obstacle_types.size() == 6);  // wall, post, vegetation, ramp, box, mesh
  CHECK(presets == std::set<std::string>{"fast", "balanced", "accurate", "fine", "finest"});
  CHECK(couplings.size() == 2);
  CHECK(car_counts == std::set<std::size_t>{1, 2, 3});
  CHECK(slowest_kmh == 0);
  CHECK(fastest_kmh > 200);
  CHECK(lowest_hz < 80);
  CHECK(highest_hz > 1500);
  CHECK(car_to_car > 30);
  CHECK(with_drive > 100);
}

TEST_CASE("random scenes: footprints apart by the gap between them, overlapping ones by a negative gap",
          "[random]") {
  const sandbox::Footprint a{{0, 0}, 0, {1, 1}};
  CHECK(sandbox::footprintGap_m(a, {{3, 0}, 0, {0.5, 0.5}}) == Approx(1.5));
  CHECK(sandbox::footprintGap_m(a, {{1.2, 0.5}, 0.7, {0.5, 0.5}}) < 0);
  // Turned 45 degrees, a unit square reaches sqrt(2) along X.
  CHECK(sandbox::footprintGap_m(a, {{3, 0}, 0.25 * 3.14159265358979, {0.5, 0.5}}) ==
        Approx(2 - 0.5 * std::sqrt(2.0)));
}
