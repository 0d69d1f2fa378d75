// Two bodies stepped as one (deform/body_group.hpp): the contacts between their surfaces move both sides,
// so the momentum they exchange is equal and opposite at every step, two identical bodies meeting head-on
// crush alike (no leader), and neither passes into the other.
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/body_group.hpp>
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>

using namespace deform;
using namespace dynamics_test;

namespace {

struct Frame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position_m{0, 0, 0}, velocity_mps{0, 0, 0};
};

Eigen::Vector3d pointsMomentum(const BodySettings& settings, const BodyState& state,
                               const Eigen::Vector3d& frame_mps) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < settings.pointCount(); ++i)
    p += settings.mass_kg[i] * (state.velocities_mps[i] + frame_mps);
  return p;
}

struct HeadOn {
  double crush_a_m = 0, crush_b_m = 0;  ///< how far each front came back [m]
  double plastic_a_J = 0, plastic_b_J = 0;
  double worst_momentum_error = 0;  ///< |J_a + R J_b| / |J_a| over the steps with contact
  double deepest_m = 0;             ///< deepest a place of one surface was found inside the other [m]
  double closing_after_mps = 0;     ///< the cores' closing speed at the end [m/s]
};

/// Two sedan bodies of `points` control points (a 400 kg shell on a 1100 kg core each), fronts 2 cm
/// apart, closing at `speed_mps` each, stepped as a group for 0.2 s at 500 Hz.
HeadOn headOn(std::size_t points, double speed_mps) {
  const ControlMesh mesh = sedanControlMesh(points);
  BodyDescription description;
  description.max_deviation_m = 0.6;
  description.anchored_columns = true;
  const auto settings = makeSettings(mesh, 400.0, description);
  SolverParams params;
  params.inertial_scale = 0;
  params.sleep_delay_s = -1;
  params.yield_limited = true;
  DeformableBody a(settings, params), b(settings, params);
  double front = -1e9;
  for (const auto& p : mesh.points_m) front = std::max(front, p.x());

  const double core_kg = 1100, dt = 1.0 / 500;
  Frame fa, fb;
  fb.rotation = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  fb.position_m = {2 * front + 0.02, 0, 0};
  fa.velocity_mps = {speed_mps, 0, 0};
  fb.velocity_mps = {-speed_mps, 0, 0};
  HeadOn out;
  for (int k = 0; k < 100; ++k) {
    fa.position_m += fa.velocity_mps * dt;
    fb.position_m += fb.velocity_mps * dt;
    StepInputs ia, ib;
    ia.core_mass_kg = ib.core_mass_kg = core_kg;
    BodyLink link;
    link.rotation_b_to_a = fa.rotation.transpose() * fb.rotation;
    link.translation_b_to_a_m = fa.rotation.transpose() * (fb.position_m - fa.position_m);
    link.velocity_mps = fa.rotation.transpose() * (fb.velocity_mps - fa.velocity_mps);
    link.friction = 0.3;
    const Eigen::Vector3d before_a = pointsMomentum(*settings, a.state(), Eigen::Vector3d::Zero());
    const Eigen::Vector3d before_b = pointsMomentum(*settings, b.state(), Eigen::Vector3d::Zero());
    std::vector<LinkReport> links;
    const std::vector<StepReport> r = stepGroup({&a, &b}, {&ia, &ib}, {link}, dt, &links);
    REQUIRE(r.size() == 2);
    REQUIRE(links.size() == 1);
    // Each body: the points' momentum changed by what the contacts gave them less what the core took.
    for (int side = 0; side < 2; ++side) {
      const DeformableBody& body = side == 0 ? a : b;
      const Eigen::Vector3d after = pointsMomentum(*settings, body.state(), r[side].core_velocity_mps);
      const Eigen::Vector3d from_core =
          (after - (side == 0 ? before_a : before_b)) - r[side].contact_impulse_Ns;
      CHECK((from_core + r[side].core_impulse_Ns).norm() <=
            1e-9 * std::max(1.0, r[side].core_impulse_Ns.norm()));
    }
    // Between the bodies: equal and opposite, in the world.
    const Eigen::Vector3d on_a = fa.rotation * r[0].contact_impulse_Ns;
    const Eigen::Vector3d on_b = fb.rotation * r[1].contact_impulse_Ns;
    if (on_a.norm() > 0) {
      out.worst_momentum_error = std::max(out.worst_momentum_error, (on_a + on_b).norm() / on_a.norm());
      CHECK((links[0].impulse_on_a_Ns - r[0].contact_impulse_Ns).norm() <= 1e-9 * on_a.norm());
    }
    out.deepest_m = std::max(out.deepest_m, links[0].deepest_m);
    fa.velocity_mps += fa.rotation * r[0].core_impulse_Ns / core_kg;
    fb.velocity_mps += fb.rotation * r[1].core_impulse_Ns / core_kg;
    fa.position_m += fa.rotation * r[0].core_displacement_m;
    fb.position_m += fb.rotation * r[1].core_displacement_m;
  }
  double front_a = -1e9, front_b = -1e9;
  for (const auto& p : a.state().positions_m) front_a = std::max(front_a, p.x());
  for (const auto& p : b.state().positions_m) front_b = std::max(front_b, p.x());
  out.crush_a_m = front - front_a;
  out.crush_b_m = front - front_b;
  out.plastic_a_J = a.state().plastic_work_J;
  out.plastic_b_J = b.state().plastic_work_J;
  out.closing_after_mps = fa.velocity_mps.x() - fb.velocity_mps.x();
  return out;
}

}  // namespace

TEST_CASE("Two bodies in contact: equal and opposite momentum, the same crush head-on, no passing",
          "[dynamics]") {
  for (std::size_t points : {60u, 250u}) {
    const HeadOn h = headOn(points, 8.0);
    INFO(points << " points: crush " << h.crush_a_m << " / " << h.crush_b_m << " m, plastic " << h.plastic_a_J
                << " / " << h.plastic_b_J << " J, momentum error " << h.worst_momentum_error << ", deepest "
                << h.deepest_m << " m, closing after " << h.closing_after_mps << " m/s");
    CHECK(h.worst_momentum_error <= 1e-9);
    CHECK(h.crush_a_m > 0.05);  // both dented
    // No leader: the same to rounding (measured equal to 6 digits; a Gauss-Seidel contact pass gave
    // 49 / 35 kJ, the contact solved last deciding which body crushed).
    CHECK(std::abs(h.crush_a_m - h.crush_b_m) <= 1e-3 * std::max(h.crush_a_m, h.crush_b_m));
    CHECK(std::abs(h.plastic_a_J - h.plastic_b_J) <= 1e-3 * std::max(h.plastic_a_J, h.plastic_b_J));
    CHECK(h.deepest_m <= 0.02);      // a's points stay out of b (within a couple of centimetres)
    CHECK(h.closing_after_mps < 0);  // the crash ended: the cores part
  }
}

TEST_CASE("A bad link is refused, naming it", "[dynamics]") {
  const auto settings = makeSettings(icosahedron(), 100.0, BodyDescription{});
  DeformableBody a(settings), b(settings);
  StepInputs in;
  BodyLink link;
  link.b = 0;
  CHECK_THROWS_WITH(stepGroup({&a, &b}, {&in, &in}, {link}, 0.01), Catch::Contains("links[0]"));
  link.b = 1;
  link.rotation_b_to_a(0, 0) = 2;
  CHECK_THROWS_WITH(stepGroup({&a, &b}, {&in, &in}, {link}, 0.01), Catch::Contains("rotation_b_to_a"));
  link.rotation_b_to_a.setIdentity();
  link.friction = -1;
  CHECK_THROWS_WITH(stepGroup({&a, &b}, {&in, &in}, {link}, 0.01), Catch::Contains("friction"));
}

/// A 60-point sedan body with a 400 kg shell and anchored columns, and how far its front is from its core
/// along x [m].
std::pair<std::shared_ptr<const BodySettings>, double> sedanShell60() {
  const ControlMesh mesh = sedanControlMesh(60);
  BodyDescription description;
  description.anchored_columns = true;
  double front = -1e9;
  for (const auto& p : mesh.points_m) front = std::max(front, p.x());
  return {makeSettings(mesh, 400.0, description), front};
}

TEST_CASE("A body against an obstacle takes substeps no longer than longest_contact_substep_s",
          "[dynamics]") {
  // A wall met at 8 m/s at 120 Hz: 4 substeps capped at a twelfth of the step are 12 substeps, bit for
  // bit; with nothing in contact the cap does nothing.
  const auto shell = sedanShell60();  // no structured binding: clang 14 cannot capture one in a lambda
  const std::shared_ptr<const BodySettings>& settings = shell.first;
  const double front = shell.second;
  const double dt = 1.0 / 120;
  auto drive = [&](uint32_t substeps, double longest_s, bool wall) {
    SolverParams params;
    params.yield_limited = true;
    params.substeps = substeps;
    params.longest_contact_substep_s = longest_s;
    DeformableBody body(settings, params);
    for (int k = 0; k < 12; ++k) {
      StepInputs in;
      in.core_mass_kg = 1100;
      in.chassis.gravity_mps2 = {0, 0, -9.81};
      if (wall) {
        BoxShape box;
        box.centre_m = {front + 0.51 - 8 * dt * (k + 1), 0, 0};
        box.half_extents_m = {0.5, 3, 3};
        in.contacts = {box};
        in.contact_velocity_mps = {{-8, 0, 0}};
        in.surface_contact = {1};
      }
      body.step(in, dt);
    }
    return hashState(body.state());
  };
  CHECK(drive(4, dt / 12, true) == drive(12, HUGE_VAL, true));
  CHECK(drive(4, dt / 12, true) != drive(4, HUGE_VAL, true));
  CHECK(drive(4, dt / 12, false) == drive(4, HUGE_VAL, false));
}

TEST_CASE("A group's substeps are no longer than its bodies' longest_contact_substep_s", "[dynamics]") {
  // Two bodies meeting head-on at 120 Hz: 4 substeps capped at a twelfth of the step are the same solve,
  // bit for bit, as 12 substeps asked for; the cap is checked like the other knobs.
  const auto shell = sedanShell60();  // no structured binding: clang 14 cannot capture one in a lambda
  const std::shared_ptr<const BodySettings>& settings = shell.first;
  const double front = shell.second;
  const double dt = 1.0 / 120;
  auto meet = [&](uint32_t substeps, double longest_s) {
    SolverParams params;
    params.yield_limited = true;
    params.substeps = substeps;
    params.longest_contact_substep_s = longest_s;
    DeformableBody a(settings, params), b(settings, params);
    BodyLink link;
    link.rotation_b_to_a = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    link.velocity_mps = {-16, 0, 0};
    link.friction = 0.3;
    StepInputs ia, ib;
    ia.core_mass_kg = ib.core_mass_kg = 1100;
    for (int k = 0; k < 12; ++k) {
      link.translation_b_to_a_m = {2 * front + 0.02 - 16 * dt * (k + 1), 0, 0};
      stepGroup({&a, &b}, {&ia, &ib}, {link}, dt);
    }
    REQUIRE(a.state().plastic_work_J > 0);  // they met
    return std::make_pair(hashState(a.state()), hashState(b.state()));
  };
  CHECK(meet(4, dt / 12) == meet(12, HUGE_VAL));
  CHECK(meet(4, dt / 12) != meet(4, HUGE_VAL));
  SolverParams params;
  for (double bad : {0.0, -1e-3, std::numeric_limits<double>::quiet_NaN()}) {
    params.longest_contact_substep_s = bad;
    CHECK_THROWS_WITH(DeformableBody(settings, params), Catch::Contains("longest_contact_substep_s"));
  }
}
