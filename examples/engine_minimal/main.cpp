// The ten-line integration of deform into an engine (docs/LIBRARY.md): a 200 kg deformable box dropped
// from 0.5 m onto a static slab. The engine owns the rigid body (here a point mass falling under
// gravity); deform gets the slab in the body's frame each step, and hands back the momentum the body
// passed to its core. Prints the permanent dent and checks that it is physical: finite, positive,
// within the visual constraint, and the box has come to rest on the slab.
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/deformable_body.hpp>
#include <deform/masses.hpp>
#include <deform/skin.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

int main() {
  const double dt_s = 1.0 / 500, gravity_mps2 = -9.81, slab_top_m = 0.0;
  double height_m = 0.75, speed_mps = 0.0;  // the box's centre (its core) in the world; world velocity

  // --- the integration (docs/LIBRARY.md) ---
  const deform::Mesh mesh = deform::makeBox({1.0, 1.0, 0.5}, 4000);  // or deform::loadVehicleModel(file)
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3f& v : mesh.positions_m) points.push_back(v.cast<double>());
  const deform::ControlMesh control = deform::buildControlMesh(points, 120, "box");
  const auto settings = std::make_shared<const deform::BodySettings>(
      deform::createBodySettings(control, deform::distributeMass(control, 200.0), deform::BodyDescription{}));
  deform::DeformableBody body(settings);
  for (int step = 0; step < 1000; ++step) {  // 2 s
    speed_mps += gravity_mps2 * dt_s;        // the engine moves its rigid body ...
    height_m += speed_mps * dt_s;
    deform::StepInputs inputs;  // ... and hands deform the slab in the body's frame, where it ends the step
    inputs.contacts = {deform::HalfSpaceShape{{0, 0, 1}, slab_top_m - height_m}};
    inputs.contact_velocity_mps = {{0, 0, -speed_mps}};  // the slab's velocity relative to the body
    inputs.core_mass_kg = settings->core_mass_kg;        // the core is pushed back by what the body takes
    const deform::StepReport report = body.step(inputs, dt_s);
    speed_mps += report.core_velocity_mps.z();  // the reaction on the rigid body
    height_m += report.core_displacement_m.z();
  }
  const double dent_m = deform::maxDeviation(*settings, body.state());  // the permanent dent
  deform::Skin skin = deform::Skin::build(mesh.positions_m, settings->rest_positions_m, {});
  std::vector<Eigen::Vector3d> displacements(settings->pointCount());
  for (std::size_t i = 0; i < displacements.size(); ++i)
    displacements[i] = body.state().positions_m[i] - settings->rest_positions_m[i];
  std::vector<Eigen::Vector3f> skinned(mesh.positions_m.size());
  skin.deform(mesh.positions_m.data(), displacements.data(), skinned.data());  // the dented render mesh
  // --- end of the integration ---

  // The skin is a convex combination of the control points' displacements (idw weights sum to one): no
  // render vertex moves further than the furthest control point.
  double vertex_moved_m = 0, lowest_point_m = INFINITY;
  for (std::size_t j = 0; j < skinned.size(); ++j)
    vertex_moved_m = std::max(vertex_moved_m, static_cast<double>((skinned[j] - mesh.positions_m[j]).norm()));
  for (const Eigen::Vector3d& p : body.state().positions_m)
    lowest_point_m = std::min(lowest_point_m, height_m + p.z());
  const double impact_energy_J = 200.0 * 9.81 * 0.5;
  const double cap_m = settings->max_deviation_m.front();
  std::printf("box 1.0 x 1.0 x 0.5 m, 200 kg, dropped 0.5 m onto a slab (impact at %.2f m/s)\n",
              std::sqrt(2 * 9.81 * 0.5));
  std::printf("permanent dent: %.1f mm (visual cap %.0f mm), plastic work %.1f J\n", dent_m * 1e3,
              cap_m * 1e3, body.state().plastic_work_J);
  std::printf("at rest: centre %.3f m above the slab, speed %.4f m/s, lowest control point %.1f mm from it\n",
              height_m - slab_top_m, speed_mps, (lowest_point_m - slab_top_m) * 1e3);
  std::printf("skinned render mesh: %zu vertices, the furthest moved %.1f mm\n", skinned.size(),
              vertex_moved_m * 1e3);

  int failures = 0;
  auto require = [&](bool ok, const char* what) {
    if (!ok) {
      std::fprintf(stderr, "engine_minimal: FAILED: %s\n", what);
      ++failures;
    }
  };
  require(std::isfinite(dent_m) && dent_m > 1e-4, "a finite permanent dent over 0.1 mm");
  require(dent_m <= cap_m * (1 + 1e-9), "the dent within the visual constraint");
  require(body.state().plastic_work_J > 0, "plastic work done");
  require(body.state().plastic_work_J < impact_energy_J, "less plastic work than the drop's energy m g h");
  require(std::abs(speed_mps) < 0.05, "the box at rest (under 5 cm/s)");
  require(height_m > slab_top_m && height_m < 0.25 + 1e-6, "the box resting on the slab, not through it");
  require(lowest_point_m > slab_top_m - 0.005, "no control point more than 5 mm inside the slab");
  require(vertex_moved_m > 0 && vertex_moved_m <= dent_m + 1e-6, "the skin moved no vertex beyond the dent");
  return failures == 0 ? 0 : 1;
}
