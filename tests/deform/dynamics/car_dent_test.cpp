// A dent stays where the car was hit: a pole pushed 15 cm into the middle of the front bumper of the
// built-in sedan (200 control points) leaves a permanent dent there, and the rear of the car untouched.
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/deformable_body.hpp>
#include <deform/masses.hpp>

using namespace deform;

TEST_CASE("a pole pushed into the front leaves a local permanent dent", "[dynamics]") {
  const VehicleModel car = makeSedan(5000);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : car.body.positions_m) points.push_back(p.cast<double>());
  const ControlMesh mesh = buildControlMesh(points, 200, "sedan");
  const auto settings = dynamics_test::makeSettings(mesh, 1500.0, BodyDescription{});
  double front = -1e9, rear = 1e9, centre_z = 0;
  for (const auto& p : mesh.points_m) {
    front = std::max(front, p.x());
    rear = std::min(rear, p.x());
  }
  for (const auto& p : mesh.points_m)
    if (p.x() > front - 0.2) centre_z = p.z();  // a height on the front face
  DeformableBody body(settings);
  StepInputs inputs;
  inputs.contact_friction = 0.3;  // steel on steel: the pole carries the skin back, not aside
  const double depth = 0.15, radius = 0.2;
  for (int k = 0; k < 90; ++k) {
    const double x = front + radius - depth * std::min(1.0, (k + 1) / 30.0);  // in at 0.3 m/s, then held
    inputs.contacts = {CapsuleShape{{x, 0, centre_z - 1}, {x, 0, centre_z + 1}, radius}};
    body.step(inputs, 1.0 / 60);
  }
  double pressed = 0;
  for (std::size_t i = 0; i < settings->pointCount(); ++i)
    pressed = std::max(pressed, settings->rest_positions_m[i].x() - body.state().positions_m[i].x());
  WARN("pressed " << pressed);
  inputs.contacts.clear();
  for (int k = 0; k < 120; ++k) body.step(inputs, 1.0 / 60);

  double dent = 0, rear_motion = 0;
  for (std::size_t i = 0; i < settings->pointCount(); ++i) {
    const Eigen::Vector3d& x0 = settings->rest_positions_m[i];
    const double moved = (body.state().positions_m[i] - x0).norm();
    if (x0.x() > front - 0.3 && std::abs(x0.y()) < radius)
      dent = std::max(dent, x0.x() - body.state().positions_m[i].x());
    if (x0.x() < 0.5 * (front + rear)) rear_motion = std::max(rear_motion, moved);
  }
  WARN("pole 15 cm into the front: permanent dent " << dent * 100 << " cm, rear half moved at most "
                                                    << rear_motion * 1e3 << " mm, plastic work "
                                                    << body.state().plastic_work_J << " J");
  CHECK(dent > 0.05);           // a lasting dent of more than a third of the push
  CHECK(dent <= depth + 0.01);  // not deeper than the pole went
  CHECK(rear_motion < 0.005);   // the rear half stays within 5 mm of where it was
  CHECK(body.state().plastic_work_J > 0);
}
