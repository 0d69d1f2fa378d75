// Sleep by default (issue 42, part 4; DeformationSettings::skip_when_idle): a body with nothing within its
// margin sleeps, and it wakes before any first contact, up to 500 km/h. Each crash runs twice, sleeping
// (the default) and with skip_when_idle false: in the step of the first contact with what it meets the
// body was awake and ran its solver (it slept through steps of the approach before), and the plastic
// work of the first 10 ms of contact is the same as without sleep within a stated tolerance.
#include <vehicle/simulation.hpp>

#include "crash_cars.hpp"

#include <deform/builtin_meshes.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

using namespace vehicle;
using crash_test::frontOf;
using crash_test::kKmh;
using crash_test::sedan;

namespace {

constexpr double kTopSpeed_mps = 500 * kKmh;
/// How far the plastic work of a sleeping run's first 10 ms of contact may be from the same run's with
/// skip_when_idle false [1]: the sleeping body meets the obstacle with its shell as it fell asleep (its
/// sag frozen), the other with the shell it kept solving; measured at most 1.6 % apart (a post at
/// 500 Hz). Later the two runs part: a car crushed to its rigid parts at 500 km/h is thrown about, and its
/// plastic work at the end differed by up to 50 % either way.
constexpr double kPlasticTolerance = 0.03;
/// The stretch of the first contact the plastic work is compared over [s]: at least the step it began in.
constexpr double kContactWindow_s = 0.01;
/// The crashing car's travel before it meets what it hits [s].
constexpr double kApproach_s = 0.3;

/// One car's approach and first contact.
struct Watched {
  CarId id = 0;
  int contact_step = -1;            ///< the step its first contact happened in (-1: none)
  uint64_t slept_before = 0;        ///< steps its body slept through before that step
  bool asleep_at_contact = false;   ///< its body was asleep when that step began ...
  bool solved_at_contact = false;   ///< ... and it ran the solver in that step
  std::vector<double> plastic_J{};  ///< its plastic work after each step from that one on [J]
  bool diverged = false;
};

/// Steps `sim` `steps` times, watching the cars `ids`.
std::vector<Watched> stepWatching(Simulation& sim, const std::vector<CarId>& ids, int steps) {
  std::vector<Watched> watched;
  for (const CarId id : ids) watched.push_back(Watched{.id = id});
  for (int k = 0; k < steps; ++k) {
    std::vector<Simulation::DeformCounts> before;
    std::vector<uint8_t> asleep;
    for (const Watched& w : watched) {
      before.push_back(sim.deformCounts(w.id));
      asleep.push_back(sim.body(w.id).state().sleeping ? 1 : 0);
    }
    sim.step();
    for (std::size_t i = 0; i < watched.size(); ++i) {
      Watched& w = watched[i];
      if (w.contact_step < 0 && sim.metrics(w.id).impacted) {
        w.contact_step = k;
        w.slept_before = before[i].skipped;
        w.asleep_at_contact = asleep[i] != 0;
        w.solved_at_contact = sim.deformCounts(w.id).steps == before[i].steps + 1;
      }
      if (w.contact_step >= 0) w.plastic_J.push_back(sim.body(w.id).state().plastic_work_J);
    }
  }
  for (Watched& w : watched) w.diverged = sim.metrics(w.id).diverged;
  return watched;
}

/// Builds a crash and hands back the cars to watch.
using Build = std::function<std::vector<CarId>(Simulation&, const DeformationSettings&)>;

/// The crash `build` at `hz` with skip_when_idle `skip`, stepped for `seconds`.
std::vector<Watched> crash(const Build& build, double hz, bool skip, double seconds) {
  WorldSettings ws;
  ws.physics_rate_hz = hz;
  Simulation sim(ws);
  DeformationSettings deformation;
  deformation.skip_when_idle = skip;
  const std::vector<CarId> ids = build(sim, deformation);
  return stepWatching(sim, ids, static_cast<int>(std::lround(seconds * hz)));
}

/// The checks of one crash at `hz`: every watched car slept during the approach, was awake and ran its
/// solver in the step of its first contact, and (with `compare`) dented over the first 10 ms of contact
/// as it does without sleep, neither run diverging.
void checkWakes(const Build& build, double hz, double seconds, bool compare = true) {
  const std::vector<Watched> sleeping = crash(build, hz, true, seconds);
  const std::vector<Watched> solved = crash(build, hz, false, seconds);
  REQUIRE(sleeping.size() == solved.size());
  const auto window = static_cast<std::size_t>(std::max(0.0, std::ceil(kContactWindow_s * hz - 1e-9) - 1));
  for (std::size_t i = 0; i < sleeping.size(); ++i) {
    const Watched& s = sleeping[i];
    const Watched& o = solved[i];
    REQUIRE(s.contact_step >= 0);
    REQUIRE(o.contact_step >= 0);
    REQUIRE(s.plastic_J.size() > window);
    REQUIRE(o.plastic_J.size() > window);
    INFO(hz << " Hz, car " << s.id << ": first contact in step " << s.contact_step << " (" << o.contact_step
            << " without sleep), slept " << s.slept_before << " steps before; plastic work "
            << s.plastic_J[window] << " J after " << window + 1 << " steps of contact against "
            << o.plastic_J[window] << " J");
    CHECK(s.slept_before > 0);  // it did sleep on the way: the test tests waking
    CHECK_FALSE(s.asleep_at_contact);
    CHECK(s.solved_at_contact);
    CHECK(s.contact_step == o.contact_step);
    if (!compare) continue;
    CHECK_FALSE(s.diverged);
    CHECK_FALSE(o.diverged);
    CHECK(o.plastic_J[window] > 0);
    CHECK(std::abs(s.plastic_J[window] - o.plastic_J[window]) <= kPlasticTolerance * o.plastic_J[window]);
  }
}

/// The sedan at the origin, driving along +x at `speed_mps`.
CarId approaching(Simulation& sim, const DeformationSettings& deformation, double speed_mps) {
  CarStart start;
  start.speed_mps = speed_mps;
  return sim.addDeformableCar(sedan(), {}, start, deformation);
}

}  // namespace

TEST_CASE("a sleeping body wakes before it meets a wall at 500 km/h", "[vehicle][idle][wake]") {
  const Build wall = [](Simulation& sim, const DeformationSettings& deformation) {
    const CarId id = approaching(sim, deformation, kTopSpeed_mps);
    const double face_m = frontOf(sim, id) + kTopSpeed_mps * kApproach_s;
    sim.world().addWall(Pose{{face_m + 0.1, 0, 1.0}, Eigen::Quaterniond::Identity()}, {0.2, 6, 2});
    return std::vector<CarId>{id};
  };
  for (const double hz : {60.0, 500.0}) checkWakes(wall, hz, kApproach_s + 0.1);
}

TEST_CASE("a sleeping body wakes before it meets a post at 500 km/h", "[vehicle][idle][wake]") {
  const Build post = [](Simulation& sim, const DeformationSettings& deformation) {
    const CarId id = approaching(sim, deformation, kTopSpeed_mps);
    sim.world().addPost({frontOf(sim, id) + kTopSpeed_mps * kApproach_s + 0.15, 0.3, 0}, 0.15, 2.0);
    return std::vector<CarId>{id};
  };
  for (const double hz : {60.0, 500.0}) checkWakes(post, hz, kApproach_s + 0.1);
}

TEST_CASE("two sleeping bodies wake before they meet: a car at 500 km/h into one at rest",
          "[vehicle][idle][wake]") {
  const Build cars = [](Simulation& sim, const DeformationSettings& deformation) {
    const CarId moving = approaching(sim, deformation, kTopSpeed_mps);
    // The parked car faces it, offset 0.4 m, its front 0.3 s of travel ahead of the moving car's front.
    CarStart parked;
    parked.position_m = {2 * frontOf(sim, moving) + kTopSpeed_mps * kApproach_s, 0.4, 0};
    parked.heading_rad = std::numbers::pi;
    const CarId at_rest = sim.addDeformableCar(sedan(), {}, parked, deformation);
    return std::vector<CarId>{moving, at_rest};
  };
  for (const double hz : {60.0, 500.0}) checkWakes(cars, hz, kApproach_s + 0.1);
}

TEST_CASE("a parked car's sleeping body wakes before a thrown box meets it", "[vehicle][idle][wake]") {
  // A 30 kg box thrown across the road at the parked car's side, at 20 m/s and at 100 m/s (1.7 m a step
  // at 60 Hz, past the broad phase's 1 m for a free obstacle).
  for (const double box_mps : {20.0, 100.0}) {
    const Build thrown = [box_mps](Simulation& sim, const DeformationSettings& deformation) {
      const CarId parked = sim.addDeformableCar(sedan(), {}, {}, deformation);
      const double flight_s = 0.35;
      const ObstacleId box =
          sim.world().addConvexMesh(deform::makeBox({0.5, 0.5, 0.5}, 100),
                                    Pose{{0, 1.2 + box_mps * flight_s, 1.4}, {1, 0, 0, 0}}, 30.0);
      sim.world().applyImpulse({EntityRef::Kind::Obstacle, box}, {0, -30.0 * box_mps, 0},
                               sim.world().obstaclePose(box).position_m);
      return std::vector<CarId>{parked};
    };
    INFO("box at " << box_mps << " m/s");
    // The energy watch marks this throw diverged with sleep and without (3.4 and 2.9 kJ created of 6.1 kJ
    // at 20 m/s and 60 Hz, 34-55 kJ of 150 kJ at 100 m/s at any rate: the crush coupling's limit with a
    // box thrown at a car's side, not sleep's); there only the waking is checked.
    checkWakes(thrown, 60.0, 0.45, false);
    checkWakes(thrown, 120.0, 0.45, false);
    checkWakes(thrown, 500.0, 0.45, box_mps < 50);
  }
}
