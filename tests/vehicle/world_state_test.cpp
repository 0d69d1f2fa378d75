// A World's saved state (world.hpp saveState / restoreState / stateHash): put back bit for bit, the
// restored world continues as the original; the hash covers time, step counter, the fixed-step
// accumulator and ODE's shuffle seed, each on its own.
#include <catch2/catch.hpp>

#include <deform/error.hpp>
#include <vehicle/state_io.hpp>
#include <vehicle/world.hpp>

#include <cstring>
#include <memory>
#include <vector>

namespace {

/// A box car at 12 m/s into a wall, a second one crossing: contacts, rigid bodies turning.
std::unique_ptr<vehicle::World> crashWorld() {
  auto world = std::make_unique<vehicle::World>();
  vehicle::CarStart start;
  start.speed_mps = 12;
  world->addBoxCar({}, start);
  vehicle::CarStart crossing;
  crossing.position_m = {6, -6, 0};
  crossing.heading_rad = 1.2;
  crossing.speed_mps = 8;
  world->addBoxCar({}, crossing);
  world->addWall(vehicle::Pose{{9, 0, 0.8}, Eigen::Quaterniond::Identity()}, {0.5, 6, 1.6});
  return world;
}

std::vector<uint8_t> saved(const vehicle::World& world) {
  vehicle::StateWriter out;
  world.saveState(out);
  return out.take();
}

void restore(vehicle::World& world, const std::vector<uint8_t>& bytes) {
  vehicle::StateReader in(bytes, "world state");
  world.restoreState(in);
  REQUIRE(in.done());
}

}  // namespace

TEST_CASE("a world restored from its saved state continues bit for bit", "[state]") {
  auto a = crashWorld();
  for (int i = 0; i < 600; ++i) a->step();

  auto b = crashWorld();
  int taken = 0;
  while (taken < 600 && b->contacts().empty()) {
    b->step();
    ++taken;
  }
  for (int i = 0; i < 10; ++i, ++taken) b->step();
  REQUIRE(taken < 600);
  CHECK_FALSE(b->contacts().empty());  // saved with a contact going on
  const std::vector<uint8_t> bytes = saved(*b);
  auto c = crashWorld();
  restore(*c, bytes);
  CHECK(c->stateHash() == b->stateHash());
  CHECK(saved(*c) == bytes);
  for (int i = taken; i < 600; ++i) c->step();
  CHECK(c->stateHash() == a->stateHash());
  CHECK(c->time_s() == a->time_s());
}

TEST_CASE("the world's state hash changes with the time, the step counter, the accumulator or the seed alone",
          "[state]") {
  auto world = crashWorld();
  for (int i = 0; i < 20; ++i) world->step();
  const std::vector<uint8_t> bytes = saved(*world);
  // Layout: car count, obstacle count (u64 each), time, accumulator (double), steps, seed (u64).
  const std::size_t offsets[] = {16, 24, 32, 40};
  for (std::size_t at : offsets) {
    INFO("byte offset " << at);
    std::vector<uint8_t> changed = bytes;
    changed[at] ^= 1;
    auto other = crashWorld();
    restore(*other, changed);
    CHECK(other->stateHash() != world->stateHash());
  }
  double later = 0;
  std::memcpy(&later, bytes.data() + 16, sizeof later);
  std::vector<uint8_t> changed = bytes;
  later += 1.0;
  std::memcpy(changed.data() + 16, &later, sizeof later);
  auto other = crashWorld();
  restore(*other, changed);
  CHECK(other->time_s() == later);
  CHECK(other->stepCount() == world->stepCount());

  auto clock = crashWorld();
  const uint64_t before = clock->stateHash();
  CHECK(clock->advance(0.4 * clock->fixedDt_s()) == 0);  // only the accumulator moves
  CHECK(clock->stateHash() != before);
}

TEST_CASE("a saved world state that does not fit the world is refused", "[state]") {
  auto world = crashWorld();
  const std::vector<uint8_t> bytes = saved(*world);
  vehicle::World empty;
  vehicle::StateReader in(bytes, "world state");
  CHECK_THROWS_AS(empty.restoreState(in), deform::InputError);
  std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2));
  auto other = crashWorld();
  vehicle::StateReader short_in(cut, "world state");
  CHECK_THROWS_WITH(other->restoreState(short_in), Catch::Contains("world state: truncated"));
}
