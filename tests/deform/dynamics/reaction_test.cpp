// Reaction, not bookkeeping (DESIGN.md section 5): the core is a heavy particle inside the substeps, and
// the momentum the body hands it is exactly what the spokes, the shell orientation, the visual constraint
// and the damping took from the points. Only the obstacles add momentum.
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/deformable_body.hpp>

using namespace deform;
using namespace dynamics_test;

namespace {

Eigen::Vector3d momentum(const BodySettings& settings, const BodyState& state, const Eigen::Vector3d& frame) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < settings.pointCount(); ++i)
    p += settings.mass_kg[i] * (state.velocities_mps[i] + frame);
  return p;
}

}  // namespace

TEST_CASE("Newton's third law between the core and the body, step by step", "[dynamics]") {
  const VehicleModel car = makeSedan(2000);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : car.body.positions_m) points.push_back(p.cast<double>());
  const ControlMesh mesh = buildControlMesh(points, 120, "sedan");
  const auto settings = makeSettings(mesh, 400.0, BodyDescription{});
  SolverParams params;
  params.inertial_scale = 0;
  params.sleep_delay_s = -1;
  DeformableBody body(settings, params);
  double front = -1e9;
  for (const auto& p : mesh.points_m) front = std::max(front, p.x());

  // A wall closing at 15 m/s (in the vehicle frame) on a 1500 kg core, and a post beside it.
  const double core_mass_kg = 1500, dt = 1.0 / 500;
  Eigen::Vector3d core_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d total_core = Eigen::Vector3d::Zero();
  for (int k = 0; k < 60; ++k) {
    StepInputs inputs;
    const double wall_x = front + 0.05 - (15.0 - core_velocity.x()) * dt * (k + 1);
    BoxShape wall;
    wall.centre_m = {wall_x + 0.5, 0, 0};
    wall.half_extents_m = {0.5, 0.4, 3.0};
    inputs.contacts = {wall};
    inputs.surface_contact = {1};
    inputs.contact_velocity_mps = {Eigen::Vector3d(-15.0 + core_velocity.x(), 0, 0)};
    inputs.core_mass_kg = core_mass_kg;
    inputs.contact_friction = 0.3;
    const Eigen::Vector3d before = momentum(*settings, body.state(), Eigen::Vector3d::Zero());
    const StepReport r = body.step(inputs, dt);
    // The points' momentum in the step's frame (the state is re-centred on the core afterwards).
    const Eigen::Vector3d after = momentum(*settings, body.state(), r.core_velocity_mps);
    const Eigen::Vector3d exchanged = (after - before) - r.contact_impulse_Ns;  // what the core gave them
    INFO("step " << k << ": core took " << r.core_impulse_Ns.transpose() << " N s, points got "
                 << exchanged.transpose() << " N s from it");
    const double scale = std::max(1.0, r.core_impulse_Ns.norm());
    CHECK((r.core_impulse_Ns + exchanged).norm() <= 1e-9 * scale);
    // The heavy core moved by what it took (its velocity comes from its positions: rounding of 1e-12 m
    // over a 0.5 ms substep, times 1500 kg).
    CHECK((r.core_velocity_mps * core_mass_kg - r.core_impulse_Ns).norm() <= 1e-7 * scale);
    // The obstacles' momentum, per obstacle, adds up to the total (each one's reaction goes back to it).
    REQUIRE(r.contact_impulse_per_obstacle_Ns.size() == 1);
    CHECK((r.contact_impulse_per_obstacle_Ns[0] - r.contact_impulse_Ns).norm() <= 1e-9 * scale);
    core_velocity += r.core_velocity_mps;
    total_core += r.core_impulse_Ns;
  }
  // The wall pushed the core back: the crush decelerates the chassis.
  CHECK(total_core.x() < -100.0);
}
