// The random crash campaign (`sandbox stress --random`) on fixed seeds: every scene played twice must hold
// every invariant (energy not created beyond 5 % of the energy through the run, no launch past the
// ballistic bound, finite, no tunnelling, the same hash). Scenes that break one are physics to fix, not
// seeds to change.
#include <stress/random_campaign.hpp>

#include <catch2/catch.hpp>

#include <cstdio>
#include <iterator>
#include <utility>

namespace {

// Scenes 0 .. kScenes-1 of each of the seeds 1 to 5: 60 scenes, about 35 s on one core here
// (docs/STABILITY.md), one test per seed so that `ctest -j` spreads them. Under AddressSanitizer (make
// test-asan) all 60 took 9.6 min: there the first 3 of each seed (15 scenes) look for memory errors, and the
// Release suite holds all 60 to the physics.
constexpr std::size_t kReleaseScenes = 12;
#if defined(__SANITIZE_ADDRESS__)
constexpr std::size_t kScenes = 3;
#else
constexpr std::size_t kScenes = kReleaseScenes;
#endif

void playSeed(uint64_t seed) {
  if (kScenes < kReleaseScenes)
    std::printf("[fewer under AddressSanitizer] seed %llu: scenes 0 to %zu of the Release suite's 0 to %zu\n",
                static_cast<unsigned long long>(seed), kScenes - 1, kReleaseScenes - 1);
  for (std::size_t i = 0; i < kScenes; ++i) {
    const sandbox::RandomOutcome outcome = sandbox::runRandomScene(seed, i);
    INFO(outcome.scene.name << ": " << sandbox::randomTableRow(outcome)
                            << "\n  scene: " << outcome.scene.document.dump());
    CHECK(outcome.passed);
  }
}

}  // namespace

TEST_CASE("random crash campaign, seed 1: every scene holds every invariant", "[random][campaign]") {
  playSeed(1);
}
TEST_CASE("random crash campaign, seed 2: every scene holds every invariant", "[random][campaign]") {
  playSeed(2);
}
TEST_CASE("random crash campaign, seed 3: every scene holds every invariant", "[random][campaign]") {
  playSeed(3);
}
TEST_CASE("random crash campaign, seed 4: every scene holds every invariant", "[random][campaign]") {
  playSeed(4);
}
TEST_CASE("random crash campaign, seed 5: every scene holds every invariant", "[random][campaign]") {
  playSeed(5);
}

TEST_CASE("random crash campaign: the scenes that broke an invariant hold them now", "[random][regression]") {
  // Each found by `sandbox stress --random 100 --seed S` (docs/STABILITY.md, "What broke, and what
  // changed"), with what it broke then.
  const std::pair<uint64_t, std::size_t> broken[] = {
      {7, 2},     // a visual car into a crush car taken as immovable: 216 kJ created (18.7 %)
      {7, 17},    // a crush car into a visual car standing by a wall: 13.6 kJ (8.6 %)
      {7, 43},    // three cars, crush and visual: 188 kJ (132 % by the cars' own books)
      {8, 55},    // two crush cars, a wheel's ray on the side of the other's hull: 62 kJ (21.9 %)
      {7, 14},    // a visual car into a crush car at 170 km/h: 124 kJ (38 %)
      {8, 54},    // a 628 kg tree at 213 km/h, stopped at the caps as if it stood still: 266 kJ (16.6 %)
      {8, 71},    // a tree and a wall at 204 km/h: 876 kJ (8.1 %)
      {11, 232},  // a 1.9 t tree pushed at 10 km/h, moved at its trunk's speed, pushed at its centre: 51.7 %
      {11, 957},  // a free box, a visual car and a ramp at 127-189 km/h: 302 kJ (12.7 %)
      {11, 540},  // two crush cars and a tree, the two bodies' contacts throwing deep places out: 39.6 %
      {10, 13},   // a car glancing off a short wall's end, taken as tunnelled by a chord through the wall
      {11, 671},  // three cars, one taken as tunnelled the same way
  };
  // Under AddressSanitizer the first two (13 s here for the seven in Release), as the campaign's scenes.
#if defined(__SANITIZE_ADDRESS__)
  const std::size_t replayed = 2;
  std::printf(
      "[fewer under AddressSanitizer] the first %zu of the %zu scenes (the Release suite replays all)\n",
      replayed, std::size(broken));
#else
  const std::size_t replayed = std::size(broken);
#endif
  for (std::size_t k = 0; k < replayed; ++k) {
    const auto& [seed, i] = broken[k];
    const sandbox::RandomOutcome outcome = sandbox::runRandomScene(seed, i);
    INFO(outcome.scene.name << ": " << sandbox::randomTableRow(outcome));
    CHECK(outcome.passed);
  }
}
