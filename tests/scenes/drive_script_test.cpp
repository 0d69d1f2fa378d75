// Drive scripts: nothing before the first key, throttle/brake/steering linear between keys, the last key
// held, speed control from a key with a target speed.
#include <catch2/catch.hpp>

#include <scenes/drive_script.hpp>

TEST_CASE("drive keys: none before the first, linear between, held after the last", "[scenes]") {
  scenes::DriveScript script;
  scenes::DriveKey a;
  a.t_s = 1.0;
  scenes::DriveKey b;
  b.t_s = 2.0;
  b.brake = 1.0;
  b.steering = -0.5;
  b.handbrake = true;
  script.keys = {a, b};
  scenes::DrivePlayer player(script);
  const vehicle::DriverInput before = player.inputs(0.5, 10, 0.002);
  CHECK(before.brake == 0);
  CHECK(before.throttle == 0);
  const vehicle::DriverInput middle = player.inputs(1.5, 10, 0.002);
  CHECK(middle.brake == Approx(0.5));
  CHECK(middle.steering == Approx(-0.25));
  CHECK_FALSE(middle.handbrake);
  const vehicle::DriverInput after = player.inputs(5.0, 10, 0.002);
  CHECK(after.brake == 1.0);
  CHECK(after.steering == -0.5);
  CHECK(after.handbrake);
}

TEST_CASE("a key with a target speed drives the pedals by the speed controller", "[scenes]") {
  scenes::DriveKey hold;
  hold.target_speed_kmh = 36;  // 10 m/s
  scenes::DrivePlayer player({{hold}});
  CHECK(player.inputs(0.1, 5.0, 0.002).throttle > 0.5);  // too slow: accelerate
  const vehicle::DriverInput fast = player.inputs(0.2, 15.0, 0.002);
  CHECK(fast.throttle == 0);
  CHECK(fast.brake > 0);  // too fast: brake
}
