// Friction holds a point to the obstacle's surface, which moves and turns in the body's frame
// (StepInputs::contact_velocity_mps, contact_angular_velocity_radps), not to the frame itself.
#include "fixtures.hpp"

#include <catch2/catch.hpp>

using namespace deform;
using namespace dynamics_test;

namespace {

/// A floor 2 cm into the bottom of a 1 m sphere hull (a kinematic core), moving in the body's frame at
/// `velocity_mps` and turning at `omega_radps` about the core, for 20 steps at 500 Hz. Returns the mean
/// displacement [m] of the points it holds from their rest places, and (out) the floor's own velocity at
/// their mean place.
Eigen::Vector3d heldPointsDrag(double friction, const Eigen::Vector3d& velocity_mps,
                               const Eigen::Vector3d& omega_radps, Eigen::Vector3d& floor_mps) {
  const auto settings = makeSettings(sphereHull(200, 1.0), 100.0, BodyDescription{}, elasticMaterial(1e-4));
  SolverParams params;
  params.substeps = 4;
  params.iterations = 2;
  DeformableBody body(settings, params);
  HalfSpaceShape floor;
  floor.normal = {0, 0, 1};
  floor.offset_m = -0.98;  // n . x = offset: the floor's surface, 2 cm above the bottom point
  StepInputs inputs;
  inputs.contacts = {floor};
  inputs.contact_velocity_mps = {velocity_mps};
  inputs.contact_angular_velocity_radps = {omega_radps};
  inputs.contact_friction = friction;
  for (int k = 0; k < 20; ++k) body.step(inputs, 1.0 / 500);
  Eigen::Vector3d moved = Eigen::Vector3d::Zero(), place = Eigen::Vector3d::Zero();
  int held = 0;
  for (std::size_t i = 0; i < settings->pointCount(); ++i)
    if (settings->rest_positions_m[i].z() < -0.98) {
      moved += body.state().positions_m[i] - settings->rest_positions_m[i];
      place += body.state().positions_m[i];
      ++held;
    }
  REQUIRE(held > 0);
  floor_mps = velocity_mps + omega_radps.cross(place / held - settings->core_m);
  return moved / held;
}

}  // namespace

TEST_CASE("Friction carries a held point with a floor sliding in the body's frame", "[dynamics]") {
  Eigen::Vector3d floor_mps;
  const Eigen::Vector3d sliding{0.5, 0, 0};
  const Eigen::Vector3d free = heldPointsDrag(0.0, sliding, Eigen::Vector3d::Zero(), floor_mps);
  const Eigen::Vector3d held = heldPointsDrag(1.0, sliding, Eigen::Vector3d::Zero(), floor_mps);
  INFO("moved frictionless " << free.transpose() << ", with friction " << held.transpose() << " m");
  CHECK(std::abs(free.x()) < 1e-3);  // no friction: only the squeeze moves them, a little, any way
  // With friction the floor drags them its way, held back by the body's constraints, never past the
  // floor's own travel (0.5 m/s x 40 ms).
  CHECK(held.x() > 3e-3);
  CHECK(held.x() <= sliding.x() * 20 / 500.0);
}

TEST_CASE("Friction carries a held point with a floor that turns in the body's frame", "[dynamics]") {
  // A floor turning about the core (as the ground does for a car that pitches) moves under the bottom
  // point at omega x r: friction must drag the point that way, although the floor's velocity at the
  // core is zero.
  Eigen::Vector3d floor_mps;
  const Eigen::Vector3d omega{0, 0.5, 0};  // r = (0, 0, -1): the floor moves at -0.5 m/s along x there
  const Eigen::Vector3d free = heldPointsDrag(0.0, Eigen::Vector3d::Zero(), omega, floor_mps);
  const Eigen::Vector3d held = heldPointsDrag(1.0, Eigen::Vector3d::Zero(), omega, floor_mps);
  INFO("floor " << floor_mps.transpose() << " m/s; moved frictionless " << free.transpose()
                << ", with friction " << held.transpose() << " m");
  REQUIRE(floor_mps.x() < -0.4);
  CHECK(std::abs(free.x()) < 1e-3);
  CHECK(held.x() < -3e-3);
  CHECK(held.x() >= floor_mps.x() * 20 / 500.0);
}
