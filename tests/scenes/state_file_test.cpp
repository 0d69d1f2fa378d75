// Save and resume (scene_run.hpp, state_file.cpp): a run resumed from a state file ends bit for bit as
// the uninterrupted run, mid-impact too; a file that is truncated, corrupted, of a newer format, of
// another scene or of other settings is refused naming the file, and changes nothing.
#include <catch2/catch.hpp>

#include <deform/error.hpp>
#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "scene_helpers.hpp"

namespace {

using scene_test::scene;

nlohmann::json withoutTimings(nlohmann::json summary) {
  summary.erase("timing_ms");
  summary.erase("deform_steps");  // counts the resumed part only, like timing_ms
  return summary;
}

/// Steps `run` until every car has hit something, then `after_s` further: a time within the impact.
void stepIntoImpact(scenes::SceneRun& run, double after_s) {
  auto impacted = [&run] {
    for (std::size_t i = 0; i < run.carCount(); ++i)
      if (!run.simulation().metrics(run.carId(i)).impacted) return false;
    return true;
  };
  while (!run.finished() && !impacted()) run.step();
  REQUIRE(impacted());
  const double contact_s = run.time_s();
  run.stepUntil(contact_s + after_s);
  std::printf("[figure] %s: first contact at %.3f s, state saved at %.3f s\n", run.scene().name.c_str(),
              contact_s, run.time_s());
  REQUIRE_FALSE(run.finished());
}

/// Uninterrupted (A), saving at `after_s` past the impact (B) and resumed from B's file (C): C's hash
/// right after the restore is B's at the save, and A, B and C end with the same hash and summary.
void checkResume(const scenes::SceneConfig& config, double after_s) {
  scenes::SceneRun a(config);
  a.runToEnd();

  scenes::SceneRun b(config);
  stepIntoImpact(b, after_s);
  const std::vector<uint8_t> file = b.stateFile();
  const uint64_t saved_hash = b.stateHash();
  const uint64_t saved_steps = b.steps();
  // Mid-impact: the first car still closes on what it hit.
  CHECK(b.simulation().metrics(b.carId(0)).max_dynamic_crush_m > 0.05);
  b.runToEnd();
  CHECK(b.stateHash() == a.stateHash());  // saving changes nothing

  scenes::SceneRun c(config);
  c.restoreState(file, "resume.state");
  CHECK(c.stateHash() == saved_hash);
  CHECK(c.steps() == saved_steps);
  c.runToEnd();
  CHECK(scenes::hashHex(c.stateHash()) == scenes::hashHex(a.stateHash()));
  CHECK(withoutTimings(c.summary()) == withoutTimings(a.summary()));
}

}  // namespace

TEST_CASE("a wall crash resumed mid-impact ends bit for bit as the uninterrupted run", "[state]") {
  checkResume(scene("wall_crash", {"duration_s=0.5"}), 0.12);
}

TEST_CASE("a car-to-car crash resumed mid-impact ends bit for bit as the uninterrupted run", "[state]") {
  checkResume(scene("car_to_car", {"duration_s=0.9"}), 0.1);
}

TEST_CASE("a run resumed after its collision hull was rebuilt from the dent ends bit for bit", "[state]") {
  // wall_crash: the car rolls back off the wall and brakes; its hull follows the dent once it is quiet;
  // then it drives into the wall again (at about 7 km/h near 2 s) with the rebuilt hull.
  const scenes::SceneConfig config =
      scene("wall_crash", {"duration_s=2.3", R"(vehicle.drive.keys=[{"t_s": 0.8}, {"t_s": 1.0, "brake": 0.6},
                     {"t_s": 1.45}, {"t_s": 1.5, "throttle": 1}])"});
  scenes::SceneRun a(config);
  a.runToEnd();
  scenes::SceneRun fresh(config);
  scenes::SceneRun b(config);
  b.stepUntil(1.4);
  const auto& rest = fresh.simulation().world().car(fresh.carId(0)).collisionHull().points_m;
  const auto& now = b.simulation().world().car(b.carId(0)).collisionHull().points_m;
  REQUIRE((now.size() != rest.size() || now != rest));  // re-hulled before the save
  const std::vector<uint8_t> file = b.stateFile();
  scenes::SceneRun c(config);
  c.restoreState(file, "rehulled.state");
  CHECK(c.stateHash() == b.stateHash());
  c.runToEnd();
  CHECK(c.stateHash() == a.stateHash());
  CHECK(withoutTimings(c.summary()) == withoutTimings(a.summary()));
  // The second impact dented it further.
  CHECK(a.summary()["residual_crush_m"].get<double>() >
        b.simulation().metrics(b.carId(0)).residual_crush_m + 0.003);
}

TEST_CASE("a resumed run with free obstacles ends bit for bit: a tree knocked over, its sleep countdown",
          "[state]") {
  // post_bumps: the sedan at 15 km/h under speed control knocks a small tree over near 1 s.
  const scenes::SceneConfig config = scene("post_bumps", {"duration_s=1.6"});
  scenes::SceneRun a(config);
  a.runToEnd();
  scenes::SceneRun b(config);
  b.stepUntil(1.1);
  const std::vector<uint8_t> file = b.stateFile();
  const uint64_t saved_hash = b.stateHash();
  scenes::SceneRun c(config);
  c.restoreState(file, "trees.state");
  CHECK(c.stateHash() == saved_hash);
  c.runToEnd();
  CHECK(c.stateHash() == a.stateHash());
  CHECK(withoutTimings(c.summary()) == withoutTimings(a.summary()));
  // The tree moved (it was hit before the save).
  const vehicle::World& world = a.simulation().world();
  CHECK(world.obstaclePose(a.obstacleId(0)).orientation.angularDistance(Eigen::Quaterniond::Identity()) >
        0.1);
}

TEST_CASE("a resumed run's hash right after the restore is the saved run's, at the start too", "[state]") {
  const scenes::SceneConfig config = scene("wall_crash", {"duration_s=0.1"});
  scenes::SceneRun a(config);
  scenes::SceneRun b(config);
  b.restoreState(a.stateFile(), "start.state");
  CHECK(b.stateHash() == a.stateHash());
  a.runToEnd();
  b.runToEnd();
  CHECK(b.stateHash() == a.stateHash());
}

TEST_CASE("a visual run resumed in the middle of its crash ends as the uninterrupted one", "[state]") {
  // The ghost (the car as it would move without ODE's rigid contact) is state: saved while the wall is
  // inside it, the resumed run dents on to the same hash.
  const scenes::SceneConfig config = scene("wall_crash", {"duration_s=0.4", "vehicle.coupling=visual"});
  scenes::SceneRun a(config);
  a.stepUntil(0.19);  // 20 ms after the impact: the dent is forming
  const double plastic_at_save_J = a.simulation().metrics(a.carId(0)).energy.plastic_work_J;
  const std::vector<uint8_t> file = a.stateFile();
  scenes::SceneRun b(config);
  b.restoreState(file, "visual.state");
  CHECK(b.stateHash() == a.stateHash());
  a.runToEnd();
  b.runToEnd();
  CHECK(b.stateHash() == a.stateHash());
  CHECK(plastic_at_save_J > 1e3);
  CHECK(a.simulation().metrics(a.carId(0)).energy.plastic_work_J > 2 * plastic_at_save_J);
}

TEST_CASE("state files that are truncated, corrupted, newer or foreign are refused naming the file",
          "[state]") {
  const scenes::SceneConfig config = scene("wall_crash", {"duration_s=0.2"});
  scenes::SceneRun saved(config);
  saved.stepUntil(0.1);
  const std::vector<uint8_t> file = saved.stateFile();

  scenes::SceneRun run(config);
  const uint64_t fresh_hash = run.stateHash();
  auto refused = [&run](const std::vector<uint8_t>& bytes, const std::string& why) {
    CHECK_THROWS_AS(run.restoreState(bytes, "x.state"), deform::InputError);
    CHECK_THROWS_WITH(run.restoreState(bytes, "x.state"),
                      Catch::StartsWith("x.state: ") && Catch::Contains(why));
  };

  std::vector<uint8_t> truncated = file;
  truncated.resize(file.size() - 100);
  refused(truncated, "truncated");
  truncated.resize(20);
  refused(truncated, "truncated");

  std::vector<uint8_t> flipped = file;
  flipped[flipped.size() / 2] ^= 0x10;
  refused(flipped, "corrupted");
  std::vector<uint8_t> longer = file;
  longer.push_back(0);
  refused(longer, "corrupted");

  std::vector<uint8_t> newer = file;
  newer[8] = 6;  // the format version, after the 8-byte mark
  refused(newer, "newer format version (6");

  refused(std::vector<uint8_t>{'h', 'e', 'l', 'l', 'o'}, "not a sandbox state file");
  refused({}, "not a sandbox state file");

  scenes::SceneRun other_scene(scene("car_to_car", {"duration_s=0.2"}));
  refused(other_scene.stateFile(), "a state of scene 'car_to_car'");
  scenes::SceneRun other_settings(scene("wall_crash", {"duration_s=0.2", "vehicle.start.speed_kmh=50"}));
  refused(other_settings.stateFile(), "other settings");

  CHECK(run.stateHash() == fresh_hash);  // nothing was changed by the refusals
  CHECK(run.steps() == 0);

  // A refused file leaves the run able to take a good one.
  run.restoreState(file, "x.state");
  CHECK(run.stateHash() == saved.stateHash());
}

TEST_CASE("output settings do not change a scene's settings hash; physics settings do", "[state]") {
  const uint64_t plain = scene("wall_crash", {}).settings_hash;
  CHECK(scene("wall_crash", {"outputs.fps=10", "camera.fov_deg=50"}).settings_hash == plain);
  CHECK(scene("wall_crash", {"vehicle.deformation.substeps=3"}).settings_hash != plain);
  CHECK(scene("wall_crash", {"duration_s=1.0"}).settings_hash != plain);
}

TEST_CASE("the run's state hash covers the frame clock of advance()", "[state]") {
  scenes::SceneRun run(scene("wall_crash", {"duration_s=0.1"}));
  const uint64_t before = run.stateHash();
  CHECK(run.advance(0.4 / run.scene().physics_hz) == 0);  // less than a step: only the clock moves
  CHECK(run.steps() == 0);
  CHECK(run.stateHash() != before);
}

TEST_CASE("a state file names the scene it was saved from; other files are refused naming them", "[state]") {
  const scenes::SceneConfig config = scene("wall_crash", {"duration_s=0.1"});
  scenes::SceneRun run(config);
  run.stepUntil(0.05);
  const std::string path = "state_file_test_source.state";
  run.saveState(path);
  CHECK(scenes::stateFileSceneSource(path) == config.source);
  // The source found is enough to resume the run (Python's Scene.resume(path)).
  scenes::SceneRun resumed(
      scenes::loadScene(scenes::stateFileSceneSource(path), {scenes::parseOverride("duration_s=0.1")}));
  resumed.restoreState(path);
  CHECK(resumed.stateHash() == run.stateHash());
  std::remove(path.c_str());
  CHECK_THROWS_WITH(scenes::stateFileSceneSource(path), Catch::StartsWith(path + ": cannot read"));
  const std::string text = "state_file_test_text.state";
  scenes::writeFileAtomically(text, "not a state file, but long enough to have a header's 32 bytes");
  CHECK_THROWS_WITH(scenes::stateFileSceneSource(text),
                    Catch::StartsWith(text + ": not a sandbox state file"));
  std::remove(text.c_str());
}
