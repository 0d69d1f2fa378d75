// The crush coupling: crashes against real crash-test figures, energy, tunnelling, car to car, posts.
#include <vehicle/simulation.hpp>

#include <deform/builtin_meshes.hpp>

#include <catch2/catch.hpp>

using namespace vehicle;

TEST_CASE("Simulation: a deformable car drives undamaged", "[crush]") {
  Simulation sim;
  const deform::VehicleModel model = deform::makeBuiltin("builtin:sedan?vertices=2000");
  CarStart start;
  start.speed_mps = 5;
  const CarId id = sim.addDeformableCar(model, {}, start, {});
  sim.run(0.5);
  const CrashMetrics m = sim.metrics(id);
  CHECK_FALSE(m.impacted);
  CHECK(sim.controlDisplacements(id).size() == sim.controlRestPoints(id).size());
}
