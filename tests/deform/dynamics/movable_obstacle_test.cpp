// A free obstacle inside the substeps (StepInputs::contact_inverse_mass_per_kg): it gives way to the body by
// its mass, takes the momentum it gives the points back, and does not go into what holds it
// (StepInputs::contact_held_normals).
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/control_mesh.hpp>
#include <deform/deformable_body.hpp>
#include <deform/error.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

using namespace deform;
using namespace dynamics_test;

namespace {

struct BoxRun {
  Eigen::Vector3d velocity_mps{0, 0, 0};    ///< the box's, at the end (vehicle frame)
  Eigen::Vector3d impulse_Ns{0, 0, 0};      ///< what it gave the points, summed
  Eigen::Vector3d displacement_m{0, 0, 0};  ///< off its input path, summed over the steps
  double most_along_x_m = -1e300;           ///< the largest displacement along +x in a step
  BodyState state;
};

/// A box of `box_kg` (0: immovable) closing at 8 m/s on the front of the sedan's 120-point body (its core
/// kinematic), for `steps` steps at 500 Hz. The caller's part, as the vehicle does with ODE: the box
/// moves on at its velocity, changed each step by minus the momentum it gave the points, and by the
/// displacement deform reports. `held` is passed as its held normals.
BoxRun boxIntoBody(double box_kg, int steps, const std::vector<Eigen::Vector3d>& held = {},
                   bool pass_inverse_mass = true) {
  const ControlMesh mesh = sedanControlMesh(120);
  const auto settings = makeSettings(mesh, 400.0, BodyDescription{});
  DeformableBody body(settings, SolverParams{});
  double front = -1e9;
  for (const auto& p : mesh.points_m) front = std::max(front, p.x());
  const double dt = 1.0 / 500;
  BoxRun run;
  run.velocity_mps = {-8, 0, 0};
  Eigen::Vector3d centre{front + 0.05 + 0.15, 0, 0.5};
  for (int k = 0; k < steps; ++k) {
    centre += dt * run.velocity_mps;  // where its velocity puts it at the step's end
    BoxShape box;
    box.centre_m = centre;
    box.half_extents_m = {0.15, 0.15, 0.15};
    StepInputs inputs;
    inputs.contacts = {box};
    inputs.surface_contact = {1};
    inputs.contact_velocity_mps = {run.velocity_mps};
    if (pass_inverse_mass) inputs.contact_inverse_mass_per_kg = {box_kg > 0 ? 1.0 / box_kg : 0.0};
    if (!held.empty()) inputs.contact_held_normals = {held};
    const StepReport r = body.step(inputs, dt);
    REQUIRE(r.obstacle_displacement_m.size() == 1);
    const Eigen::Vector3d moved = r.obstacle_displacement_m[0];
    centre += moved;
    run.displacement_m += moved;
    run.most_along_x_m = std::max(run.most_along_x_m, moved.x());
    run.impulse_Ns += r.contact_impulse_per_obstacle_Ns[0];
    if (box_kg > 0) run.velocity_mps -= r.contact_impulse_per_obstacle_Ns[0] / box_kg;
  }
  run.state = body.state();
  return run;
}

}  // namespace

TEST_CASE("A light free box hit by the body is knocked away: it takes no more than reversing it takes",
          "[dynamics]") {
  // 0.5 kg at 8 m/s: the body (its core held) can at most send it back at 8 m/s (restitution <= 1), 8 N s.
  // Taken as immovable inside the step it would be handed the momentum that stops the body's points.
  const BoxRun run = boxIntoBody(0.5, 100);
  INFO("impulse " << run.impulse_Ns.transpose() << " N s, box leaves at " << run.velocity_mps.transpose()
                  << " m/s");
  CHECK(run.impulse_Ns.x() < 0);  // it pushed the points in
  CHECK(-run.impulse_Ns.x() <= 2 * 0.5 * 8.0);
  CHECK(run.velocity_mps.x() >= 0);    // stopped, and going away
  CHECK(run.velocity_mps.x() <= 8.0);  // no faster than it came
  // Deform moved it within the steps: off its path, away from the body.
  CHECK(run.displacement_m.x() > 0);
}

TEST_CASE("A movable box held by a wall behind it is not pushed into the wall", "[dynamics]") {
  // The wall behind the box faces the body (its normal into the box is -x): the box may slide along it,
  // never into it. Without the hold the body pushes it back every step.
  const std::vector<Eigen::Vector3d> wall_behind = {Eigen::Vector3d(-1, 0, 0)};
  const BoxRun held = boxIntoBody(5.0, 30, wall_behind);
  const BoxRun free = boxIntoBody(5.0, 30);
  INFO("largest step along +x: held " << held.most_along_x_m << " m, free " << free.most_along_x_m << " m");
  CHECK(held.most_along_x_m <= 1e-12);
  CHECK(free.most_along_x_m > 1e-3);
  // Held, it pushes the points as an immovable box would: at least as hard as the free one.
  CHECK(-held.impulse_Ns.x() > -free.impulse_Ns.x());
}

TEST_CASE("An obstacle of zero inverse mass is the immovable one, to the bit", "[dynamics]") {
  const BoxRun zero = boxIntoBody(0.0, 40);
  const BoxRun absent = boxIntoBody(0.0, 40, {}, false);
  REQUIRE(zero.state.positions_m.size() == absent.state.positions_m.size());
  for (std::size_t i = 0; i < zero.state.positions_m.size(); ++i)
    REQUIRE(zero.state.positions_m[i] == absent.state.positions_m[i]);
  CHECK(zero.state.plastic_work_J == absent.state.plastic_work_J);
  CHECK(zero.displacement_m == Eigen::Vector3d::Zero());
}

TEST_CASE("Bad movable-obstacle inputs are refused naming the field", "[dynamics]") {
  const ControlMesh mesh = sedanControlMesh(60);
  const auto settings = makeSettings(mesh, 400.0, BodyDescription{});
  DeformableBody body(settings, SolverParams{});
  StepInputs inputs;
  inputs.contacts = {HalfSpaceShape{}};
  inputs.contact_inverse_mass_per_kg = {-1.0};
  CHECK_THROWS_WITH(body.step(inputs, 0.002), Catch::Contains("contact_inverse_mass_per_kg[0]"));
  inputs.contact_inverse_mass_per_kg = {std::nan("")};
  CHECK_THROWS_WITH(body.step(inputs, 0.002), Catch::Contains("contact_inverse_mass_per_kg[0]"));
  inputs.contact_inverse_mass_per_kg = {0.1};
  inputs.contact_held_normals = {{Eigen::Vector3d(0, 0, 0)}};
  CHECK_THROWS_WITH(body.step(inputs, 0.002), Catch::Contains("contact_held_normals[0]"));
  inputs.contact_held_normals = {{Eigen::Vector3d(std::nan(""), 0, 1)}};
  CHECK_THROWS_WITH(body.step(inputs, 0.002), Catch::Contains("contact_held_normals[0]"));
  inputs.contact_held_normals.clear();
  // The frame a shared obstacle's moves are turned by: a rotation, not a scale or a mirror.
  inputs.frame_to_world = 2.0 * Eigen::Matrix3d::Identity();
  CHECK_THROWS_WITH(body.step(inputs, 0.002), Catch::Contains("frame_to_world"));
  inputs.frame_to_world = Eigen::Vector3d(1, 1, -1).asDiagonal();
  CHECK_THROWS_WITH(body.step(inputs, 0.002), Catch::Contains("frame_to_world"));
  inputs.frame_to_world = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  CHECK_NOTHROW(body.step(inputs, 0.002));
}
