// Face contacts: an obstacle meeting the control surface between its points (StepInputs::surface_contact).
#include "fixtures.hpp"

#include <deform/constraints.hpp>
#include <deform/contact_shapes.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

using namespace deform;
using namespace dynamics_test;

TEST_CASE("Face contact projection puts the surface point on the plane, corners by inverse mass",
          "[dynamics]") {
  Eigen::Vector3d a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const double w[3] = {1.0, 1.0, 0.5};
  const Eigen::Vector3d bary{0.2, 0.3, 0.5};
  const Eigen::Vector3d normal{0, 0, -1};  // the obstacle is above: push down
  const Eigen::Vector3d surface{0, 0, -0.1};
  const double corrected = projectFaceContact(a, b, c, w, bary, normal, surface);
  CHECK(corrected == Approx(0.1));
  const Eigen::Vector3d p = bary[0] * a + bary[1] * b + bary[2] * c;
  CHECK(p.z() == Approx(-0.1));
  // Each corner moves along the normal only, in proportion to w_k bary_k.
  CHECK(a.z() / b.z() == Approx(0.2 / 0.3));
  CHECK(c.z() / b.z() == Approx(0.5 * 0.5 / 0.3));
  CHECK(a.x() == 0);
  // Already outside (below a plane higher up): nothing moves.
  CHECK(projectFaceContact(a, b, c, w, bary, normal, Eigen::Vector3d(0, 0, 0.5)) == 0);
}

TEST_CASE("A bar between the control points dents the surface only with face contacts", "[dynamics]") {
  // An icosahedron of radius 1 and a thin bar pressed 0.1 m into the middle of one face, where no
  // control point is: point contacts let it pass, face contacts push that face in.
  const auto settings = makeSettings(icosahedron(1.0), 100.0, BodyDescription{});
  const auto& t = settings->triangles.front();
  const auto& x0 = settings->rest_positions_m;
  const Eigen::Vector3d centroid = (x0[t[0]] + x0[t[1]] + x0[t[2]]) / 3.0;
  const Eigen::Vector3d n = (x0[t[1]] - x0[t[0]]).cross(x0[t[2]] - x0[t[0]]).normalized();
  // 0.3 m across: wider than it goes in, so it pushes out through its end (a box's nearest face), and
  // narrower than the face, so it reaches neither a corner nor an edge's midpoint.
  BoxShape bar;
  bar.half_extents_m = {0.15, 0.15, 0.3};
  bar.axes.col(2) = n;
  bar.axes.col(0) = n.unitOrthogonal();
  bar.axes.col(1) = n.cross(bar.axes.col(0));
  const Eigen::Vector3d touching = centroid + 0.3 * n;  // its inner end on the face

  for (const bool surface : {false, true}) {
    SolverParams params;
    params.substeps = 4;
    params.iterations = 4;
    DeformableBody body(settings, params);
    StepInputs inputs;
    inputs.surface_contact = {static_cast<uint8_t>(surface)};
    // Pressed in at 0.3 m/s to 0.1 m (an obstacle appearing deep inside would throw the points), held.
    for (int k = 1; k <= 40; ++k) {
      bar.centre_m = touching - std::min(0.1, 0.005 * k) * n;
      inputs.contacts = {bar};
      body.step(inputs, 1.0 / 60);
    }
    const auto& x = body.state().positions_m;
    const Eigen::Vector3d now = (x[t[0]] + x[t[1]] + x[t[2]]) / 3.0;
    const double pushed_in = n.dot(centroid - now);
    INFO((surface ? "face contacts" : "points only") << ": face centre pushed in " << pushed_in << " m");
    if (surface) {
      CHECK(pushed_in == Approx(0.1).margin(0.01));  // out of the bar: its 0.1 m
    } else {
      CHECK(std::abs(pushed_in) < 1e-6);  // the bar passes between the points
    }
    // Bounded: every point within the visual constraint, none faster than 2 m/s (the bar is pressed at
    // 0.3 m/s; the held contact leaves a small substep-scale oscillation).
    CHECK(worstDeviationExcess(*settings, body.state()) <= 1e-12);
    for (const auto& v : body.state().velocities_mps) CHECK(v.norm() < 2.0);
  }
}

TEST_CASE("A thin wall met faster than half its thickness per substep pushes points back, not through",
          "[dynamics]") {
  // A 0.1 m slab closing at 150 m/s on a sphere body: 0.075 m per 0.5 ms substep, 1.5 times its half
  // thickness. The face nearest a point inside is then the far one; the point must leave by the face it
  // came in by. (Faster than its whole thickness per substep, a point can pass it unseen: no swept test.)
  // The cap (1 m) is beyond the slab's travel (0.6 m), so the visual constraint never holds a point in it.
  BodyDescription description;
  description.max_deviation_m = 1.0;
  const auto settings = makeSettings(sphereHull(200, 1.0), 100.0, description);
  SolverParams params;
  params.substeps = 4;
  params.sleep_delay_s = -1;
  DeformableBody body(settings, params);
  const double dt = 1.0 / 500, speed = 150.0, half_thickness = 0.05;
  int crossed = 0;
  for (int k = 0; k < 2; ++k) {
    // The slab's near face starts 0.05 m in front of the body (x = 1.05) and moves towards -x.
    const double near_face = 1.05 - speed * dt * (k + 1);
    BoxShape slab;
    slab.centre_m = {near_face + half_thickness, 0, 0};
    slab.half_extents_m = {half_thickness, 3.0, 3.0};
    StepInputs inputs;
    inputs.contacts = {slab};
    inputs.contact_velocity_mps = {Eigen::Vector3d(-speed, 0, 0)};
    body.step(inputs, dt);
    for (const auto& p : body.state().positions_m) crossed += p.x() > near_face + 2 * half_thickness;
    INFO("step " << k << ": near face at " << near_face << " m");
    CHECK(crossed == 0);
    // And none is left inside it (beyond the contact margin).
    for (const auto& p : body.state().positions_m) CHECK(p.x() <= near_face + 0.011);
  }
}

TEST_CASE("a moving support shape's box changes nothing: the same body state, bit for bit, as without it",
          "[dynamics]") {
  // Another car's hull closing at 14 m/s on a body while its side sweeps across it at 60 m/s: through the
  // substeps the shape is placed back along its path, and its box must move with it (a box left where
  // the step ends dropped the contacts of the earlier substeps: car_to_car at 250 points changed).
  BodyDescription description;
  description.max_deviation_m = 0.5;
  const auto settings = makeSettings(sphereHull(250, 1.0), 400.0, description);
  SolverParams params;
  params.substeps = 4;
  params.sleep_delay_s = -1;
  std::vector<Eigen::Vector3d> corners;
  for (double x : {0.0, 1.6})
    for (double y : {-0.9, 0.9})
      for (double z : {-0.7, 0.7}) corners.emplace_back(x, y, z);
  const ConvexPoints hull(corners);
  auto run = [&](bool boxed) {
    DeformableBody body(settings, params);
    const double dt = 1.0 / 500, speed = 14.0, across = 60.0;
    std::vector<Eigen::Vector3d> moved = corners;
    int touched = 0;
    for (int k = 0; k < 10; ++k) {
      for (std::size_t i = 0; i < corners.size(); ++i)
        moved[i] =
            corners[i] + Eigen::Vector3d(1.0 - speed * dt * (k + 1), -0.3 - across * dt * (k + 1), 0.1);
      const ConvexPoints placed(moved);
      ConvexSupportShape shape = placed.shape();
      if (!boxed) {
        shape.box_min_m.setConstant(HUGE_VAL);
        shape.box_max_m.setConstant(-HUGE_VAL);
      }
      StepInputs inputs;
      inputs.contacts = {shape};
      inputs.contact_velocity_mps = {Eigen::Vector3d(-speed, -across, 0)};
      touched += body.step(inputs, dt).contact_points > 0;
    }
    return std::make_pair(body.state(), touched);
  };
  const auto [with_box, touched] = run(true);
  const auto [without_box, touched_without] = run(false);
  CHECK(touched > 5);
  CHECK(touched == touched_without);
  REQUIRE(with_box.positions_m.size() == without_box.positions_m.size());
  for (std::size_t i = 0; i < with_box.positions_m.size(); ++i) {
    INFO("point " << i);
    CHECK(with_box.positions_m[i] == without_box.positions_m[i]);
    CHECK(with_box.velocities_mps[i] == without_box.velocities_mps[i]);
  }
  CHECK(with_box.plastic_work_J == without_box.plastic_work_J);
}
