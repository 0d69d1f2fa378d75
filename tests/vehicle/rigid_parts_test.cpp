// The crush backstop as the car's rigid parts (DeformationSettings::rigid_parts, World::setRigidParts):
// an obstacle crushes the body until it reaches the engine block or the passenger cell, whose geometry
// stops it; the old uniform shrink of the hull stays as Backstop::ShrunkHull.
#include <vehicle/simulation.hpp>

#include "crash_cars.hpp"

#include <deform/builtin_meshes.hpp>
#include <deform/error.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>

using namespace vehicle;
using crash_test::kKmh;
using crash_test::sedan;

namespace {

/// The sedan at 100 km/h into a 0.15 m post on its centreline; the largest intrusion and the final
/// forward speed.
std::pair<double, double> postAt100(const DeformationSettings& deformation) {
  Simulation sim;
  CarStart start;
  start.speed_mps = 100 * kKmh;
  const CarId id = sim.addDeformableCar(sedan(), {}, start, deformation);
  double front = -1e300;
  for (const auto& p : sim.controlRestPoints(id)) front = std::max(front, p.x());
  sim.world().addPost({front + 0.3 + 0.15, 0, 0}, 0.15, 1.5);
  sim.run(1.0);
  return {sim.metrics(id).max_dynamic_crush_m, sim.world().car(id).velocity_mps().x()};
}

}  // namespace

TEST_CASE("Rigid parts: a post at 100 km/h is stopped by the engine block, where the block is", "[crush]") {
  // Default: the block's front at 0.82 of the length, 0.86 m behind the bumper (measured intrusion 0.79
  // m). Moved 0.29 m back (0.76), the post goes 0.17 m further in (0.96 m); the car stops in both.
  const deform::Aabb length = deform::boundingBox(sedan().body);
  const double block_depth_m = (1 - 0.82) * length.size_m().x();
  DeformationSettings deep;
  deep.rigid_parts[1].min_m.x() = 0.70;
  deep.rigid_parts[1].max_m.x() = 0.76;
  const auto [intrusion_m, speed_mps] = postAt100({});
  const auto [deep_intrusion_m, deep_speed_mps] = postAt100(deep);
  INFO("intrusion " << intrusion_m << " m (block " << block_depth_m << " m in), with the block further back "
                    << deep_intrusion_m << " m; final speed " << speed_mps << " / " << deep_speed_mps
                    << " m/s");
  CHECK(intrusion_m > 0.5);
  CHECK(intrusion_m < block_depth_m + 0.05);
  CHECK(deep_intrusion_m > intrusion_m + 0.1);
  CHECK(speed_mps < 0.5);
  CHECK(deep_speed_mps < 0.5);
}

TEST_CASE("Rigid parts: a bad box is refused, and no box leaves the car rigid", "[crush]") {
  Simulation sim;
  const CarId id = sim.addDeformableCar(sedan(), {}, {}, {});
  CHECK(sim.world().crushes(id));
  CHECK_THROWS_AS(sim.world().setRigidParts(id, {deform::Aabb{{1, 0, 0}, {0, 1, 1}}}), deform::InputError);
  CHECK_THROWS_AS(sim.world().setRigidParts(
                      id, {deform::Aabb{{0, 0, 0}, {std::numeric_limits<double>::infinity(), 1, 1}}}),
                  deform::InputError);
  sim.world().setRigidParts(id, {});
  CHECK_FALSE(sim.world().crushes(id));
  DeformationSettings hull;
  hull.backstop = Backstop::ShrunkHull;
  const CarId other = sim.addDeformableCar(sedan(), {}, {}, hull);
  CHECK(sim.world().crushes(other));
  CHECK(sim.world().crushAllowance(other) == hull.crush_allowance_m);
}
