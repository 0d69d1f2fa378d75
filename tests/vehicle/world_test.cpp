// The world: stepping checks, determinism, and obstacles of every kind.
#include "crash_cars.hpp"
#include "driving_helpers.hpp"
#include "support.hpp"

#include <vehicle/ccd_support.hpp>
#include <vehicle/world.hpp>

#include <deform/error.hpp>
#include <deform/mesh_import.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

using namespace vehicle;
using crash_test::kKmh;
using vehicle_test::drivingSedan;

namespace {

/// A scripted drive: throttle, then a turn, then the brake.
DriverInput scripted(double t) {
  DriverInput input;
  input.throttle = t < 3 ? 0.8 : 0.2;
  input.steering = t > 2 ? 0.5 * std::sin(t) : 0.0;
  input.brake = t > 5 ? 0.6 : 0.0;
  return input;
}

bool anyContactBetween(const World& world, EntityRef a, EntityRef b) {
  for (const auto& c : world.contacts())
    if ((c.a == a && c.b == b) || (c.a == b && c.b == a)) return true;
  return false;
}

}  // namespace

TEST_CASE("a time step that is zero, negative or not finite is refused, naming the field",
          "[vehicle][world]") {
  World world;
  for (double dt :
       {0.0, -0.01, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    CHECK_THROWS_AS(world.advance(dt), deform::InputError);
    CHECK_THROWS_WITH(world.advance(dt), Catch::Contains("dt_s"));
  }
  WorldSettings bad;
  bad.physics_rate_hz = 0;
  CHECK_THROWS_WITH(World(bad), Catch::Contains("physics_rate_hz"));
  bad.physics_rate_hz = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(World(bad), Catch::Contains("physics_rate_hz"));
  VehicleSettings heavy;
  heavy.mass_kg = -1;
  CHECK_THROWS_WITH(world.addBoxCar(heavy), Catch::Contains("mass_kg"));
  CHECK_THROWS_WITH(world.addWall(Pose{}, {1, -1, 1}), Catch::Contains("wall.size_m"));
  CHECK_THROWS_WITH(world.addVegetation({0, 0, 0}, 0.1, 2, 0), Catch::Contains("vegetation.mass_kg"));
}

TEST_CASE("fixed steps: advance takes as many steps as the accumulated time holds", "[vehicle][world]") {
  WorldSettings settings;
  settings.physics_rate_hz = 240;
  World world(settings);
  CHECK(world.advance(1.0 / 60) == 4);
  CHECK(world.advance(0.001) == 0);
  CHECK(world.advance(1.0 / 240) == 1);
  CHECK(world.advance(0.1) == 24);  // a 100 ms hitch is caught up
  CHECK(world.stepCount() == 29);
}

TEST_CASE("same inputs give bit-identical states; other inputs do not", "[vehicle][world][determinism]") {
  auto build = [](World& world) {
    world.addCar(drivingSedan());
    CarStart other;
    other.position_m = {12, 1.5, 0};
    world.addCar(drivingSedan(), {}, other);
    world.addWall(Pose::yawed({30, 0, 1}, 0.2), {0.5, 8, 2});
    world.addVegetation({8, -1.5, 0}, 0.06, 2.5, 15);
    world.addPost({10, 4, 0}, 0.15, 1.5);
  };
  World a, b, c;
  build(a);
  build(b);
  build(c);
  // Interleaved stepping: ODE's global shuffle seed must not leak between worlds.
  for (int i = 0; i < 3000; ++i) {
    const double t = i * a.fixedDt_s();
    a.car(0).setInput(scripted(t));
    b.car(0).setInput(scripted(t));
    DriverInput changed = scripted(t);
    changed.throttle *= 0.999;
    c.car(0).setInput(changed);
    a.step();
    b.step();
    c.step();
  }
  CHECK(a.stateHash() == b.stateHash());
  CHECK(a.stateHash() != c.stateHash());
  // The same run again in a fresh world, after all the others, gives the same hash.
  World d;
  build(d);
  for (int i = 0; i < 3000; ++i) {
    d.car(0).setInput(scripted(i * d.fixedDt_s()));
    d.step();
  }
  CHECK(d.stateHash() == a.stateHash());
  CHECK(engineMessageCount() == 0);
}

TEST_CASE("fnv1a is the reference FNV-1a 64", "[vehicle][world]") {
  CHECK(fnv1a("", 0) == 0xcbf29ce484222325ull);
  CHECK(fnv1a("a", 1) == 0xaf63dc4c8601ec8cull);
  CHECK(fnv1a("foobar", 6) == 0x85944171f73967e8ull);
}

TEST_CASE("a wall stops the car; contacts name the car and the wall", "[vehicle][world][obstacles]") {
  World world;
  CarStart start;
  start.speed_mps = 40 * kKmh;
  const CarId id = world.addCar(drivingSedan(), {}, start);
  const ObstacleId wall = world.addWall(Pose::yawed({10, 0, 1}, 0), {0.4, 6, 2});
  bool touched = false;
  for (int i = 0; i < 1500; ++i) {
    world.step();
    if (!touched && anyContactBetween(world, {EntityRef::Kind::Car, id}, {EntityRef::Kind::Obstacle, wall})) {
      touched = true;
      DriverInput brake;
      brake.brake = 1;
      world.car(id).setInput(brake);
    }
  }
  const Car& car = world.car(id);
  CHECK(touched);
  // Stopped in front of the wall (rigid contact: the crush coupling is what will let it intrude).
  const ObstacleShape shape = world.obstacleShape(wall);
  CHECK(shape.type == ShapeType::Box);
  CHECK(shape.centre_m.x() == Approx(10));
  double front = -1e9;
  for (const auto& v : car.shape().vertices_m) front = std::max(front, v.x());
  CHECK(front < 9.8 + 0.05);
  CHECK(std::abs(car.forwardSpeed_mps()) < 0.01);
}

TEST_CASE("a car at 500 km/h does not tunnel through a 0.2 m wall", "[vehicle][world][obstacles]") {
  for (double rate : {240.0, 500.0, 2000.0}) {
    WorldSettings settings;
    settings.physics_rate_hz = rate;
    World world(settings);
    CarStart start;
    start.speed_mps = 500 * kKmh;
    const CarId id = world.addCar(drivingSedan(), {}, start);
    world.addWall(Pose::yawed({8, 0, 1}, 0), {0.2, 6, 2});
    for (int i = 0; i < static_cast<int>(rate / 5); ++i) world.step();
    double front = -1e9;
    for (const auto& v : world.car(id).shape().vertices_m) front = std::max(front, v.x());
    CHECK(front < 8.1);
    CHECK(world.car(id).velocity_mps().x() < 0);  // bounced back
  }
}

TEST_CASE("vegetation stands until a car knocks it over", "[vehicle][world][obstacles]") {
  World world;
  CarStart start;
  start.speed_mps = 30 * kKmh;
  const CarId id = world.addCar(drivingSedan(), {}, start);
  const ObstacleId tree = world.addVegetation({10, 0.3, 0}, 0.08, 3.0, 25);
  const ObstacleId untouched = world.addVegetation({10, 8, 0}, 0.08, 3.0, 25);
  CHECK(world.obstacleIsDynamic(tree));
  for (int i = 0; i < 2000; ++i) world.step();
  auto tilt = [&](ObstacleId o) {
    const Eigen::Vector3d axis = world.obstaclePose(o).orientation * Eigen::Vector3d::UnitZ();
    return std::acos(std::clamp(axis.z(), -1.0, 1.0));
  };
  CHECK(tilt(tree) > 1.0);  // lying down
  // Still upright where it was planted (ODE's 1 mm contact surface layer lets it settle that much).
  CHECK(tilt(untouched) < 1e-3);
  CHECK((world.obstaclePose(untouched).position_m - Eigen::Vector3d(10, 8, 1.5)).norm() < 1e-3);
  CHECK(world.car(id).forwardSpeed_mps() > 10 * kKmh);  // a light tree barely slows a car
}

TEST_CASE("posts: cylinders and capsules stop a car", "[vehicle][world][obstacles]") {
  for (PostShape post : {PostShape::Cylinder, PostShape::Capsule}) {
    World world;
    CarStart start;
    start.speed_mps = 20 * kKmh;
    const CarId id = world.addCar(drivingSedan(), {}, start);
    const ObstacleId pole = world.addPost({8, 0, 0}, 0.15, 3.0, post);
    const ObstacleShape shape = world.obstacleShape(pole);
    CHECK(shape.type == (post == PostShape::Cylinder ? ShapeType::Cylinder : ShapeType::Capsule));
    CHECK(shape.radius_m == 0.15);
    for (int i = 0; i < 1500; ++i) world.step();
    CHECK(world.car(id).bodyPose().position_m.x() < 8);
    CHECK(std::abs(world.car(id).forwardSpeed_mps()) < 1.0);
  }
}

TEST_CASE("a one-sided ramp rolls a fast car over", "[vehicle][world][obstacles]") {
  World world;
  CarStart start;
  start.speed_mps = 70 * kKmh;
  const CarId id = world.addCar(drivingSedan(), {}, start);
  // Under the left wheels only: 0.7 m high over 3 m.
  world.addRamp(Pose::yawed({6, 0.8, 0}, 0), 3.0, 1.0, 0.7);
  double max_roll = 0;
  for (int i = 0; i < 3000; ++i) {
    world.step();
    const Eigen::Vector3d up = world.car(id).bodyPose().orientation * Eigen::Vector3d::UnitZ();
    max_roll = std::max(max_roll, std::acos(std::clamp(up.z(), -1.0, 1.0)));
  }
  std::printf("[figure] one-sided ramp at 70 km/h: largest tilt %.0f deg\n", max_roll * 180 / 3.14159265);
  CHECK(max_roll > 1.6);  // past 90 deg: on its side or roof
  CHECK(world.car(id).bodyPose().position_m.allFinite());
}

TEST_CASE("a car pushes a parked car; both report the contact", "[vehicle][world][obstacles]") {
  World world;
  CarStart start;
  start.speed_mps = 30 * kKmh;
  const CarId moving = world.addCar(drivingSedan(), {}, start);
  CarStart parked_start;
  parked_start.position_m = {8, 0, 0};
  const CarId parked = world.addCar(drivingSedan(), {}, parked_start);
  bool touched = false;
  for (int i = 0; i < 1500; ++i) {
    world.step();
    touched =
        touched || anyContactBetween(world, {EntityRef::Kind::Car, moving}, {EntityRef::Kind::Car, parked});
  }
  CHECK(touched);
  CHECK(world.car(parked).bodyPose().position_m.x() > 8.5);
  const ObstacleShape other = world.shapeOf({EntityRef::Kind::Car, parked});
  CHECK(other.type == ShapeType::Convex);
  CHECK(other.vertices_m.size() == world.car(parked).collisionHull().points_m.size());
}

TEST_CASE("obstacle shapes are world-space descriptions with exact support functions",
          "[vehicle][world][obstacles]") {
  World world;
  const ObstacleId ground = 0;
  const ObstacleId wall = world.addWall(Pose::yawed({5, 2, 1}, 0.5), {0.4, 6, 2});
  const ObstacleId post = world.addPost({-3, 1, 0}, 0.2, 2.0);
  const ObstacleId ramp = world.addRamp(Pose::yawed({0, -6, 0}, 0.3), 4.0, 2.0, 1.0);
  const ObstacleId box =
      world.addConvexMesh(deform::makeBox({1, 2, 0.5}, 200), Pose::yawed({-8, 0, 0.25}, 0), 0);

  const ObstacleShape g = world.obstacleShape(ground);
  CHECK(g.type == ShapeType::HalfSpace);
  Eigen::Vector3d normal;
  double depth = 0;
  CHECK(pointPenetration(g, {3, 4, -0.1}, normal, depth));
  CHECK(depth == Approx(0.1));

  const ObstacleShape w = world.obstacleShape(wall);
  const Eigen::Vector3d along = w.axes.col(0);  // the wall's thin axis, turned by 0.5 rad
  CHECK(along.x() == Approx(std::cos(0.5)));
  CHECK(supportPoint(w, along).dot(along) == Approx(Eigen::Vector3d(5, 2, 1).dot(along) + 0.2));
  CHECK(pointPenetration(w, Eigen::Vector3d(5, 2, 1) + 0.15 * along, normal, depth));
  CHECK(depth == Approx(0.05).margin(1e-6));
  CHECK(normal.dot(along) == Approx(1).margin(1e-6));
  CHECK_FALSE(pointPenetration(w, Eigen::Vector3d(5, 2, 1) + 0.25 * along, normal, depth));

  const ObstacleShape p = world.obstacleShape(post);
  CHECK(supportPoint(p, {0, 0, 1}).z() == Approx(2.0));
  CHECK(supportPoint(p, {1, 0, 0}).x() == Approx(-2.8));
  CHECK(pointPenetration(p, {-3.1, 1, 1}, normal, depth));
  CHECK(depth == Approx(0.1).margin(1e-6));

  const ObstacleShape r = world.obstacleShape(ramp);
  CHECK(r.type == ShapeType::Convex);
  double top = -1e9;
  for (const auto& v : r.vertices_m) top = std::max(top, v.z());
  CHECK(top == Approx(1.0));
  CHECK(supportPoint(r, {0, 0, -1}).z() == Approx(0).margin(1e-12));

  const ObstacleShape b = world.obstacleShape(box);
  CHECK(supportPoint(b, {1, 1, 1}).isApprox(Eigen::Vector3d(-7.5, 1, 0.5), 1e-6));
  // Into a car's vehicle frame and back.
  const Pose frame = Pose::yawed({1, 2, 0}, 1.0);
  const ObstacleShape local = transformShape(b, frame);
  CHECK(frame.toWorld(supportPoint(local, frame.orientation.conjugate() * Eigen::Vector3d(1, 1, 1)))
            .isApprox(Eigen::Vector3d(-7.5, 1, 0.5), 1e-9));
  const ObstacleShape g_local = transformShape(g, frame);
  CHECK(g_local.offset_m == Approx(0));
}

TEST_CASE("far from the origin the car drives exactly as at the origin", "[vehicle][world]") {
  auto run = [](const Eigen::Vector3d& origin) {
    World world;
    CarStart start;
    start.position_m = origin;
    Car& car = world.car(world.addCar(drivingSedan(), {}, start));
    for (int i = 0; i < 2000; ++i) {
      car.setInput(scripted(i * world.fixedDt_s()));
      world.step();
    }
    return Eigen::Vector3d(car.bodyPose().position_m - origin);
  };
  const Eigen::Vector3d here = run({0, 0, 0}), far = run({1e5, -1e5, 0});
  CHECK((here - far).norm() < 1e-6);
  CHECK(here.norm() > 10);
}

TEST_CASE("a convex mesh from the importer is an obstacle (jersey barrier)", "[vehicle][world][obstacles]") {
  const auto dir = test_support::testMeshesDir();
  if (!dir) {
    test_support::reportSkip("DEFORM_TEST_MESHES is not set: the jersey barrier is one of the shared meshes");
    return;
  }
  const deform::VehicleModel barrier =
      deform::loadVehicleModel(*dir + "/gazebo_jersey_barrier/meshes/jersey_barrier.dae");
  World world;
  CarStart start;
  start.speed_mps = 30 * kKmh;
  const CarId id = world.addCar(drivingSedan(), {}, start);
  // Turned across the road 10 m ahead, standing on the ground.
  const deform::Aabb box = deform::boundingBox(barrier.body);
  const Eigen::Vector3d middle = 0.5 * (box.min_m + box.max_m);
  const Eigen::Quaterniond across(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  const Pose pose{
      Eigen::Vector3d(10, 0, -box.min_m.z()) - across * Eigen::Vector3d(middle.x(), middle.y(), 0), across};
  const ObstacleId wall = world.addConvexMesh(barrier.body, pose);
  const ObstacleShape shape = world.obstacleShape(wall);
  CHECK(shape.type == ShapeType::Convex);
  CHECK(supportPoint(shape, {0, 0, -1}).z() == Approx(0).margin(1e-6));
  CHECK(supportPoint(shape, {0, 0, 1}).z() == Approx(box.size_m().z()).epsilon(1e-6));
  CHECK(supportPoint(shape, {0, 1, 0}).y() == Approx(0.5 * box.size_m().x()).epsilon(1e-6));
  bool touched = false;
  for (int i = 0; i < 1500; ++i) {
    world.step();
    touched =
        touched || anyContactBetween(world, {EntityRef::Kind::Car, id}, {EntityRef::Kind::Obstacle, wall});
  }
  CHECK(touched);
  CHECK(world.car(id).bodyPose().position_m.x() < 10);
  CHECK(engineMessageCount() == 0);
}

TEST_CASE("contacts report the force they applied: a resting box weighs on the ground", "[vehicle][world]") {
  World world;
  const ObstacleId box =
      world.addConvexMesh(deform::makeBox({1, 1, 0.5}, 200), Pose::yawed({0, 0, 0.25}, 0.3), 80);
  for (int i = 0; i < 200; ++i) world.step();  // 0.4 s: before it falls asleep (then nothing is solved)
  Eigen::Vector3d on_box = Eigen::Vector3d::Zero();
  int count = 0;
  for (const auto& c : world.contacts()) {
    const bool box_is_a = c.a == EntityRef{EntityRef::Kind::Obstacle, box};
    on_box += box_is_a ? c.force_on_a_N : Eigen::Vector3d(-c.force_on_a_N);
    ++count;
    // The normal points from b into a.
    CHECK(c.normal.z() == Approx(box_is_a ? 1.0 : -1.0).margin(1e-6));
  }
  CHECK(count >= 3);
  CHECK(on_box.z() == Approx(80 * 9.81).epsilon(0.01));
  CHECK(on_box.head<2>().norm() < 0.02 * 80 * 9.81);  // friction only balances solver noise
}

TEST_CASE("a car's contacts in its vehicle frame: the wall pushes its nose back", "[vehicle][world]") {
  World world;
  CarStart start;
  start.speed_mps = 15 * kKmh;
  start.heading_rad = 0.7;  // the vehicle frame is turned against the world
  const CarId id = world.addCar(drivingSedan(), {}, start);
  const Eigen::Vector3d ahead(std::cos(0.7), std::sin(0.7), 0);
  const ObstacleId wall = world.addWall(Pose::yawed(Eigen::Vector3d(0, 0, 1) + 8 * ahead, 0.7), {0.4, 6, 2});
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  int count = 0;
  double front = -1e9;
  for (const auto& p : world.car(id).collisionHull().points_m) front = std::max(front, p.x());
  for (int i = 0; i < 1000; ++i) {
    world.step();
    for (const CarContact& c : world.carContacts(id)) {
      if (!(c.other == EntityRef{EntityRef::Kind::Obstacle, wall})) continue;
      ++count;
      impulse += c.impulse_N_s;
      CHECK(c.normal.x() < -0.9);          // out of the wall, back along the car
      CHECK(c.point_m.x() > front - 0.3);  // at the nose
    }
  }
  CHECK(count > 0);
  // The wall took the car's momentum (and gave a little back): impulse backwards, about m v.
  CHECK(impulse.x() < -0.8 * 1500 * 15 * kKmh);
  CHECK(std::abs(impulse.y()) < 0.1 * std::abs(impulse.x()));
}
