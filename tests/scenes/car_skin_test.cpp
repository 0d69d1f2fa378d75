// The car's render mesh updates only what moved: positions and normals bit-identical to a full deform
// and a full normal recompute, for random subsets of moved control points, with either skin method.
#include <catch2/catch.hpp>

#include <scenes/car_skin.hpp>

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>

#include <cstdint>

TEST_CASE("partial skin and normal updates equal a full recompute bit for bit", "[car_skin]") {
  const deform::VehicleModel car = deform::makeSedan(8000);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : car.body.positions_m) points.push_back(p.cast<double>());
  const std::vector<Eigen::Vector3d> control = deform::buildControlMesh(points, 60).points_m;
  deform::Mesh body = car.body;
  body.normals.clear();  // normals from the triangles from the start

  for (deform::SkinMethod method : {deform::SkinMethod::idw, deform::SkinMethod::mls}) {
    CAPTURE(deform::skinMethodName(method));
    vehicle::DeformationSettings settings;
    settings.skin_method = method;
    scenes::CarSkin skin(body, control, settings);
    CHECK(skin.skin().method() == method);

    std::vector<Eigen::Vector3d> displacement(control.size(), Eigen::Vector3d::Zero());
    uint64_t seed = 7;
    auto next = [&seed] {  // fixed LCG, uniform in [0, 1)
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(seed >> 11) / 9007199254740992.0;
    };
    std::size_t partial_updates = 0;
    for (int frame = 0; frame < 12; ++frame) {
      // A few points (a dent) most frames, many on some.
      const double share = frame % 4 == 3 ? 0.5 : 0.05;
      for (auto& d : displacement)
        if (next() < share) d += 0.05 * Eigen::Vector3d(next() - 0.5, next() - 0.5, next() - 0.5);
      const std::size_t recomputed = skin.update(displacement);
      partial_updates += recomputed > 0 && recomputed < body.positions_m.size();

      deform::Mesh full = body;
      skin.skin().deform(body.positions_m.data(), displacement.data(), full.positions_m.data());
      deform::computeVertexNormals(full);
      REQUIRE(skin.positions() == full.positions_m);
      REQUIRE(skin.normals() == full.normals);
    }
    CHECK(partial_updates > 4);  // the partial path was exercised, not only full recomputes
  }
}

TEST_CASE("normals the body came with are kept until something moves, then all recomputed", "[car_skin]") {
  const deform::VehicleModel car = deform::makeSedan(3000);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : car.body.positions_m) points.push_back(p.cast<double>());
  const std::vector<Eigen::Vector3d> control = deform::buildControlMesh(points, 30).points_m;
  deform::Mesh body = car.body;
  body.normals.assign(body.positions_m.size(), Eigen::Vector3f(1, 0, 0));  // the file's own normals
  scenes::CarSkin skin(body, control, vehicle::DeformationSettings{});
  CHECK(skin.normals() == body.normals);
  std::vector<Eigen::Vector3d> displacement(control.size(), Eigen::Vector3d::Zero());
  displacement[3] = {0.02, 0, 0};
  skin.update(displacement);
  deform::Mesh full = body;
  skin.skin().deform(body.positions_m.data(), displacement.data(), full.positions_m.data());
  deform::computeVertexNormals(full);
  CHECK(skin.normals() == full.normals);
}

TEST_CASE("cars of one build share one skin and deform as with their own", "[car_skin]") {
  const deform::VehicleModel car = deform::makeSedan(4000);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : car.body.positions_m) points.push_back(p.cast<double>());
  const std::vector<Eigen::Vector3d> control = deform::buildControlMesh(points, 60).points_m;
  const vehicle::DeformationSettings settings;
  const std::shared_ptr<const deform::Skin> shared = scenes::CarSkin::buildSkin(car.body, control, settings);
  const std::shared_ptr<const scenes::CarSkin::Build> build = scenes::CarSkin::share(car.body, shared);
  scenes::CarSkin a(build), b(build);
  scenes::CarSkin own(car.body, control, settings);
  CHECK(&a.skin() == &b.skin());
  CHECK(&a.skin() != &own.skin());
  // The rest copy, triangles, adjacency and grid are the build's, held once: a car's own part is its
  // positions and normals (24 bytes per vertex) and its flags, under half of what it shares.
  CHECK(&a.triangles() == &b.triangles());
  CHECK(&a.restPositions() == &b.restPositions());
  const std::size_t vertices = car.body.positions_m.size();
  CHECK(a.ownBytes() < 32 * vertices);
  CHECK(a.ownBytes() < build->bytes() / 2);
  // Each car's mesh is its own: a dent in one leaves the other at rest.
  std::vector<Eigen::Vector3d> dent(control.size(), Eigen::Vector3d::Zero());
  dent[0] = {-0.1, 0.02, 0.0};
  dent[7] = {0.0, -0.05, 0.01};
  a.update(dent);
  own.update(dent);
  CHECK(a.positions() == own.positions());
  CHECK(a.normals() == own.normals());
  CHECK(b.positions() == car.body.positions_m);
}

TEST_CASE("a run's cars of one body, control mesh and skin settings get one build", "[car_skin]") {
  const deform::VehicleModel car = deform::makeSedan(2000);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : car.body.positions_m) points.push_back(p.cast<double>());
  const std::vector<Eigen::Vector3d> control = deform::buildControlMesh(points, 60).points_m;
  const std::vector<Eigen::Vector3d> other_control = control;  // equal values, another control mesh
  vehicle::DeformationSettings settings, sharper;
  sharper.alpha = settings.alpha + 1;
  scenes::CarSkinBuilds builds;
  const auto first = builds.get(car.body, control, settings);
  CHECK(builds.get(car.body, control, settings) == first);
  CHECK(builds.get(car.body, control, sharper) != first);
  CHECK(builds.get(car.body, other_control, settings) != first);
  CHECK(first->rest_m == car.body.positions_m);
  CHECK(first->triangles.size() == car.body.triangles.size());
}
