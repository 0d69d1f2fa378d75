// The speed controller drives the car to a target speed and holds it.
#include "driving_helpers.hpp"

#include <vehicle/driver_input.hpp>
#include <vehicle/world.hpp>

#include <catch2/catch.hpp>

using namespace vehicle;

TEST_CASE("speed controller reaches, holds and stops", "[vehicle][controller]") {
  World world;
  Car& car = world.car(world.addCar(vehicle_test::drivingSedan()));
  SpeedController controller;
  const double dt = world.fixedDt_s();
  auto drive = [&](double target, double seconds) {
    double worst = 0;
    for (int i = 0; i < static_cast<int>(seconds / dt); ++i) {
      car.setInput(controller.update(target, car.forwardSpeed_mps(), dt));
      world.step();
      if (i * dt > seconds - 3) worst = std::max(worst, std::abs(car.forwardSpeed_mps() - target));
    }
    return worst;  // largest error over the last 3 s
  };
  CHECK(drive(15, 15) < 0.2);
  CHECK(drive(8, 12) < 0.2);  // slowing down brakes
  CHECK(drive(0, 8) < 0.01);  // and holds the car
  const DriverInput hold = controller.update(0, 0, dt);
  CHECK(hold.brake == 1);
  CHECK(hold.throttle == 0);
  // Pedals are always in range.
  SpeedController fresh;
  for (double error : {-50.0, -1.0, 0.0, 1.0, 50.0}) {
    const DriverInput in = fresh.update(20, 20 - error, dt);
    CHECK(in.throttle >= 0);
    CHECK(in.throttle <= 1);
    CHECK(in.brake >= 0);
    CHECK(in.brake <= 1);
  }
}
