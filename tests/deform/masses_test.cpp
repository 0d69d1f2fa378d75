#include <deform/control_mesh.hpp>
#include <deform/error.hpp>
#include <deform/masses.hpp>

#include <catch2/catch.hpp>
#include <cmath>

#include "point_sets.hpp"

TEST_CASE("masses sum to the vehicle mass and the core takes a quarter", "[masses]") {
  for (std::size_t target : {4u, 60u, 1000u}) {
    auto mesh = deform::buildControlMesh(test_points::sphere(800, {2.4, 0.9, 0.7}), target);
    auto split = deform::distributeMass(mesh, 1500.0);
    CHECK(split.total_kg() == Approx(1500.0).epsilon(1e-12));
    // Each tetrahedron gives one quarter to the centre, so the core holds a quarter of the whole.
    CHECK(split.core_mass_kg == Approx(375.0).epsilon(1e-12));
    for (double m : split.point_mass_kg) CHECK(m > 0);
  }
}

TEST_CASE("a cube's corners share the shell mass by their tetrahedra", "[masses]") {
  std::vector<Eigen::Vector3d> cube;
  for (int i = 0; i < 8; ++i) cube.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  auto mesh = deform::convexHull(cube);
  auto split = deform::distributeMass(mesh, 800.0);
  // 24 equal tets (each face fanned from its centre): a corner is in 6 of them, a face centre in 4.
  const double tet_kg = 800.0 / 24.0;
  for (std::size_t i = 0; i < mesh.points_m.size(); ++i) {
    const bool corner = mesh.points_m[i].cwiseAbs().minCoeff() == 1.0;
    CHECK(split.point_mass_kg[i] == Approx((corner ? 6 : 4) * tet_kg / 4.0));
  }
}

TEST_CASE("a mirror-symmetric body gets mirror-symmetric masses", "[masses]") {
  auto points = test_points::mirroredInY(test_points::sphere(600, {2.4, 0.9, 0.7}));
  // The hull itself (600 points) and every level of detail, coarser and finer.
  for (std::size_t target : {600u, 8u, 31u, 60u, 250u, 2000u}) {
    CAPTURE(target);
    auto mesh = deform::buildControlMesh(points, target);
    if (target != 600) CHECK(mesh.mirror_of.size() == mesh.points_m.size());
    auto split = deform::distributeMass(mesh, 1500.0);
    double left = 0, right = 0;
    for (std::size_t i = 0; i < mesh.points_m.size(); ++i) {
      const auto& p = mesh.points_m[i];
      if (p.y() > 1e-12) left += split.point_mass_kg[i];
      if (p.y() < -1e-12) right += split.point_mass_kg[i];
      // The mirror point exists and carries the same mass.
      Eigen::Vector3d mirror(p.x(), -p.y(), p.z());
      std::size_t nearest = 0;
      for (std::size_t k = 1; k < mesh.points_m.size(); ++k)
        if ((mesh.points_m[k] - mirror).norm() < (mesh.points_m[nearest] - mirror).norm()) nearest = k;
      REQUIRE((mesh.points_m[nearest] - mirror).norm() < 1e-12);
      CHECK(split.point_mass_kg[nearest] == Approx(split.point_mass_kg[i]).epsilon(1e-9));
    }
    CHECK(left == Approx(right).epsilon(1e-9));
  }
}

TEST_CASE("a mass that is not finite and positive is refused", "[masses]") {
  auto mesh = deform::buildControlMesh(test_points::sphere(100), 20);
  CHECK_THROWS_AS(deform::distributeMass(mesh, 0.0), deform::InputError);
  CHECK_THROWS_AS(deform::distributeMass(mesh, -5.0), deform::InputError);
  CHECK_THROWS_AS(deform::distributeMass(mesh, std::nan("")), deform::InputError);
}
