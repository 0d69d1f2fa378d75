// Shared builds (car_build.hpp; DESIGN.md section 8): cars with the same mesh and shaping settings share
// one immutable control mesh, masses and body settings; only state is per car.
#include <vehicle/car_build.hpp>
#include <vehicle/simulation.hpp>

#include "crash_cars.hpp"

#include <catch2/catch.hpp>

using namespace vehicle;
using crash_test::sedan;

namespace {

CarStart startAt(double y_m) {
  CarStart start;
  start.position_m = {0, y_m, 0};
  return start;
}

}  // namespace

TEST_CASE("Two cars with the same mesh and settings share one body settings object", "[vehicle][build]") {
  Simulation sim;
  VehicleSettings car;
  car.mass_kg = 1500;
  const CarId a = sim.addDeformableCar(sedan(), car, startAt(0), {});
  const CarId b = sim.addDeformableCar(sedan(), car, startAt(5), {});
  CHECK(&sim.body(a).settings() == &sim.body(b).settings());
  CHECK(&sim.controlMesh(a) == &sim.controlMesh(b));
  // State is per car.
  CHECK(&sim.body(a).state() != &sim.body(b).state());
}

TEST_CASE("A different shaping setting gives its own build", "[vehicle][build]") {
  Simulation sim;
  VehicleSettings car;
  car.mass_kg = 1500;
  DeformationSettings coarse, fine;
  fine.control_points = 90;
  const CarId a = sim.addDeformableCar(sedan(), car, startAt(0), coarse);
  const CarId b = sim.addDeformableCar(sedan(), car, startAt(5), fine);
  CHECK(&sim.body(a).settings() != &sim.body(b).settings());
  VehicleSettings heavier = car;
  heavier.mass_kg = 1600;
  const CarId c = sim.addDeformableCar(sedan(), heavier, startAt(10), coarse);
  CHECK(&sim.body(a).settings() != &sim.body(c).settings());
  // A setting that does not shape the body (the solver's substeps) shares it.
  DeformationSettings more_substeps = coarse;
  more_substeps.substeps = 8;
  const CarId d = sim.addDeformableCar(sedan(), car, startAt(15), more_substeps);
  CHECK(&sim.body(a).settings() == &sim.body(d).settings());
}

TEST_CASE("The build key tells meshes and materials apart", "[vehicle][build]") {
  const VehicleSettings car;
  const DeformationSettings deformation;
  CHECK(carBuildKey(sedan(), car, deformation) == carBuildKey(sedan(), car, deformation));
  deform::VehicleModel moved = sedan();
  moved.body.positions_m[0].x() += 1e-3f;
  CHECK(carBuildKey(moved, car, deformation) != carBuildKey(sedan(), car, deformation));
  DeformationSettings softer = deformation;
  softer.material.crush_strength_Pa *= 0.5;
  CHECK(carBuildKey(sedan(), car, softer) != carBuildKey(sedan(), car, deformation));
}
