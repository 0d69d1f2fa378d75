// Solid mass properties (vehicle/mass_properties.hpp) and the chassis built from them.
#include "driving_helpers.hpp"

#include <vehicle/mass_properties.hpp>
#include <vehicle/world.hpp>

#include <deform/control_mesh.hpp>
#include <deform/error.hpp>

#include <catch2/catch.hpp>

#include <cstdio>
#include <limits>

using namespace vehicle;

namespace {

deform::ControlMesh boxMesh(const Eigen::Vector3d& size, const Eigen::Vector3d& centre) {
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back(centre + 0.5 * Eigen::Vector3d((i & 1) ? size.x() : -size.x(),
                                                     (i & 2) ? size.y() : -size.y(),
                                                     (i & 4) ? size.z() : -size.z()));
  return deform::convexHull(corners, "box");
}

}  // namespace

TEST_CASE("solid properties of a box are exact, anywhere", "[vehicle][mass]") {
  const Eigen::Vector3d size(4.6, 1.8, 1.3);
  for (const Eigen::Vector3d& centre : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1e5, -2e4, 3)}) {
    const deform::ControlMesh box = boxMesh(size, centre);
    const SolidProperties p = solidProperties(box.points_m, box.triangles);
    CHECK(p.volume_m3 == Approx(size.prod()).epsilon(1e-9));
    CHECK((p.centroid_m - centre).norm() < 1e-9 * (1 + centre.norm()));
    const Eigen::Vector3d sq = size.cwiseProduct(size);
    CHECK(p.inertia_per_kg(0, 0) == Approx((sq.y() + sq.z()) / 12).epsilon(1e-6));
    CHECK(p.inertia_per_kg(1, 1) == Approx((sq.x() + sq.z()) / 12).epsilon(1e-6));
    CHECK(p.inertia_per_kg(2, 2) == Approx((sq.x() + sq.y()) / 12).epsilon(1e-6));
    CHECK(std::abs(p.inertia_per_kg(0, 1)) < 1e-6);
  }
  // Parallel axis: moving 1 m along X adds m to Iyy and Izz.
  const Eigen::Matrix3d shifted = shiftedInertia(Eigen::Matrix3d::Identity(), 2.0, {1, 0, 0});
  CHECK(shifted(0, 0) == Approx(1));
  CHECK(shifted(1, 1) == Approx(3));
  CHECK(shifted(2, 2) == Approx(3));
  // Inside-out surfaces are refused.
  deform::ControlMesh inside_out = boxMesh(size, {0, 0, 0});
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  CHECK_THROWS_AS(solidProperties(inside_out.points_m, inside_out.triangles), deform::InputError);
}

TEST_CASE("the sedan's chassis: hull mass properties, wheels from the model", "[vehicle][mass]") {
  World world;
  const Car& car = world.car(world.addCar(vehicle_test::drivingSedan()));
  const Eigen::Vector3d com = car.centreOfMass_m();
  const Eigen::Matrix3d inertia = car.inertia_kg_m2();
  std::printf(
      "[figure] sedan: hull of %zu points, centre of mass (%.3f, %.3f, %.3f) m, inertia diag (%.0f, %.0f, "
      "%.0f) kg m^2, wheelbase %.2f m, track %.2f m\n",
      car.collisionHull().points_m.size(), com.x(), com.y(), com.z(), inertia(0, 0), inertia(1, 1),
      inertia(2, 2), car.wheelbase_m(), car.track_m());
  CHECK(car.mass_kg() == 1500);
  CHECK(std::abs(com.y()) < 1e-3);  // symmetric car
  CHECK(com.z() > 0.4);
  CHECK(com.z() < 0.8);
  // A sedan's yaw inertia is about 2000-3500 kg m^2, roll 400-800, pitch close to yaw.
  CHECK(inertia(2, 2) > 2000);
  CHECK(inertia(2, 2) < 3500);
  CHECK(inertia(0, 0) > 300);
  CHECK(inertia(0, 0) < 900);
  CHECK(car.wheelSettings().size() == vehicle_test::drivingSedan().wheels.size());
  CHECK(car.wheelbase_m() == Approx(2.8).epsilon(0.01));
  int driven = 0, steered = 0;
  for (const auto& w : car.wheelSettings()) {
    driven += w.driven ? 1 : 0;
    steered += w.steered ? 1 : 0;
    CHECK(w.steered != w.driven);  // front steers, rear drives
  }
  CHECK(driven == 2);
  CHECK(steered == 2);
}

TEST_CASE("without a mesh: a box chassis with wheels from its bounding box", "[vehicle][mass]") {
  World world;
  VehicleSettings settings;
  settings.mass_kg = 1200;
  Car& car = world.car(world.addBoxCar(settings));
  CHECK(car.wheelSettings().size() == 4);
  const Eigen::Vector3d size = settings.box_size_m;
  CHECK(car.inertia_kg_m2()(2, 2) ==
        Approx(1200 * (size.x() * size.x() + size.y() * size.y()) / 12).epsilon(1e-6));
  DriverInput input;
  input.throttle = 0.5;
  car.setInput(input);
  for (int i = 0; i < 1000; ++i) world.step();
  CHECK(car.forwardSpeed_mps() > 5);
  CHECK(std::abs(vehicle_test::roll_rad(car.bodyPose())) < 0.01);
}

TEST_CASE("the collision hull can be replaced (crushed shape) without changing mass", "[vehicle][mass]") {
  World world;
  Car& car = world.car(world.addCar(vehicle_test::drivingSedan()));
  deform::ControlMesh crushed = car.collisionHull();
  double front = -1e9;
  for (const auto& p : crushed.points_m) front = std::max(front, p.x());
  for (auto& p : crushed.points_m)
    if (p.x() > front - 0.5) p.x() -= 0.3;
  const Eigen::Matrix3d inertia = car.inertia_kg_m2();
  car.setCollisionHull(crushed);
  CHECK(car.inertia_kg_m2() == inertia);
  double new_front = -1e9;
  for (const auto& v : car.shape().vertices_m)
    new_front = std::max(new_front, car.vehiclePose().toLocal(v).x());
  CHECK(new_front == Approx(front - 0.3));
  for (int i = 0; i < 200; ++i) world.step();
  CHECK(car.bodyPose().position_m.allFinite());
}

TEST_CASE("settings that cannot drive are refused with the field named", "[vehicle][mass]") {
  VehicleSettings s;
  s.tyre.friction_coefficient = 0;
  CHECK_THROWS_WITH(checkVehicleSettings(s, "car.json"),
                    Catch::Contains("car.json") && Catch::Contains("friction"));
  s = {};
  s.wheels = wheelsFromBoundingBox({{-2, -1, 0.2}, {2, 1, 1.4}});
  s.wheels[2].spring_N_per_m = -5;
  CHECK_THROWS_WITH(checkVehicleSettings(s), Catch::Contains("wheels[2].spring_N_per_m"));
  s.wheels.resize(2);
  s.wheels[1].spring_N_per_m = 1;
  CHECK_THROWS_WITH(checkVehicleSettings(s), Catch::Contains("at least 3"));
  s = {};
  s.steer_rate_rad_s = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(checkVehicleSettings(s), Catch::Contains("steer_rate_rad_s"));
}
