// The random crash campaign (`sandbox stress --random`) on fixed seeds: every scene played twice must hold
// every invariant (energy not created beyond 5 % of the energy through the run, no launch past the
// ballistic bound, finite, no tunnelling, the same hash). Scenes that break one are physics to fix, not
// seeds to change. One known gap (docs/STABILITY.md, "Random crash campaigns"): where two cars' bodies
// meet, their books can hold more plastic work and contact loss than their motion lost; those scenes are
// held to every other invariant, and their count may not grow.
#include <stress/random_campaign.hpp>

#include <catch2/catch.hpp>

#include <sstream>
#include <string>

namespace {

// Scenes 0 .. kScenes-1 of each seed: 60 scenes, about 35 s on one core here (docs/STABILITY.md). Under
// AddressSanitizer (make test-asan) they took 9.6 min: there the first 3 of each seed (15 scenes) look for
// memory errors, and the Release suite holds all 60 to the physics.
const uint64_t kSeeds[] = {1, 2, 3, 4, 5};
#if defined(__SANITIZE_ADDRESS__)
constexpr std::size_t kScenes = 3;
#else
constexpr std::size_t kScenes = 12;
#endif
// Scenes of these seeds where two cars met and only the energy check failed, measured when the campaign
// came in (random_1_9, random_2_4, random_3_4, random_3_6).
constexpr int kKnownTwoCarEnergyFailures = 4;

// Whether every failure of `outcome` is the energy check's.
bool onlyEnergy(const sandbox::RandomOutcome& outcome) {
  std::istringstream failures(outcome.failures);
  std::string failure;
  bool any = false;
  while (std::getline(failures, failure, ';')) {
    if (failure.find_first_not_of(' ') == std::string::npos) continue;
    if (failure.find("created") == std::string::npos) return false;
    any = true;
  }
  return any;
}

}  // namespace

TEST_CASE("random crash campaign: every scene of the fixed seeds holds every invariant",
          "[random][campaign]") {
  int two_car_energy_failures = 0;
  for (const uint64_t seed : kSeeds) {
    for (std::size_t i = 0; i < kScenes; ++i) {
      const sandbox::RandomOutcome outcome = sandbox::runRandomScene(seed, i);
      INFO(outcome.scene.name << ": " << sandbox::randomTableRow(outcome)
                              << "\n  scene: " << outcome.scene.document.dump());
      const bool cars_met = outcome.scene.outline.targets.find("car") != std::string::npos;
      if (!outcome.passed && cars_met && onlyEnergy(outcome)) {
        WARN("two cars met, energy check failed: " << sandbox::randomTableRow(outcome));
        ++two_car_energy_failures;
        continue;
      }
      CHECK(outcome.passed);
    }
  }
  CHECK(two_car_energy_failures <= kKnownTwoCarEnergyFailures);
}
