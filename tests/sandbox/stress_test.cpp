// The [extreme] group: `sandbox stress --quick`, one test per range. Each case checks physical
// invariants on what it measured (finite, bounded, no tunnelling, deviation within the visual
// constraint, energy not created, same hash twice, plus the group's own; stress_suite.cpp).
#include <stress/stress_suite.hpp>

#include <catch2/catch.hpp>

#include <cstdio>

namespace {

void requireGroup(const std::string& group, bool quick = true) {
  const std::vector<sandbox::StressCase> cases = sandbox::runStressGroup(group, quick);
  REQUIRE_FALSE(cases.empty());
  for (const sandbox::StressCase& c : cases) {
    INFO(c.group << " / " << c.name << ": checks " << c.checks << "\n  measured: " << c.detail);
    CHECK(c.passed);
  }
}

}  // namespace

TEST_CASE("extreme: impact speed 0 to 500 km/h into a wall", "[extreme]") {
  requireGroup("impact_speed");
}
TEST_CASE("extreme: physics rate 15 to 2000 Hz, and a 100 ms hitch", "[extreme]") {
  requireGroup("physics_rate");
}
TEST_CASE("extreme: skin alpha 0.5 and 16 on a crushed car", "[extreme]") {
  requireGroup("skin_alpha");
}
TEST_CASE("extreme: 4 and 2000 control points", "[extreme]") {
  requireGroup("control_points");
}
TEST_CASE("extreme: a 1 kg and a 40 t car", "[extreme]") {
  requireGroup("vehicle_mass");
}
TEST_CASE("extreme: the scene 1e5 m from the origin", "[extreme]") {
  requireGroup("far_from_origin");
}
TEST_CASE("extreme: degenerate and malformed meshes", "[extreme]") {
  requireGroup("meshes");
}
TEST_CASE("extreme: a long drive ending parked", "[extreme]") {
  requireGroup("long_run");
}
TEST_CASE("extreme: repeated impacts in the same spot", "[extreme]") {
  requireGroup("repeated_impacts");
}

TEST_CASE("stress: an unknown group is refused", "[extreme]") {
  CHECK_THROWS_AS(sandbox::runStressGroup("nonsense", true), std::invalid_argument);
}
TEST_CASE("soak: 1e5 steps with 50 impacts into the same spot, the same hash twice, memory flat",
          "[extreme]") {
  // The full group, not the quick one: 50 impacts, then braked to 100,000 steps at 500 Hz (200 s
  // simulated), run twice (8 s here). Under AddressSanitizer half of each (stress_driving.cpp).
#if defined(__SANITIZE_ADDRESS__)
  std::printf("[fewer under AddressSanitizer] 25 impacts and 50,000 steps, not 50 and 100,000\n");
#endif
  requireGroup("repeated_impacts", false);
}
