#include <deform/builtin_meshes.hpp>

#include <catch2/catch.hpp>

#include "mesh_report.hpp"

TEST_CASE("mesh report of the built-in sedan measures what it says", "[mesh_report]") {
  const auto car = deform::makeBuiltin("builtin:sedan?vertices=5000");
  sandbox::MeshReportOptions options;
  options.control_points = 60;
  options.vehicle_mass_kg = 1500;
  options.skin = {3.5, 8, 2};
  const auto r = sandbox::meshReport(car, options);
  CHECK(r["vertices"].get<std::size_t>() == car.body.positions_m.size());
  CHECK(r["triangles"].get<std::size_t>() == car.body.triangles.size());
  CHECK(r["control_points"].get<std::size_t>() == 60);
  CHECK(r["hull_vertices"].get<std::size_t>() > 60);
  CHECK(r["bbox_max"][0].get<double>() - r["bbox_min"][0].get<double>() == Approx(4.8).epsilon(0.01));
  CHECK(r["weights_sum_max_error"].get<double>() < 1e-6);
  CHECK(r["translation_error_max_m"].get<double>() < 1e-5);
  CHECK(r["mass"]["core_kg"].get<double>() + r["mass"]["points_total_kg"].get<double>() == Approx(1500.0));
  CHECK(r["mirror_symmetric"].get<bool>());
  // An even spread: no hole much larger than the even spacing for 60 points over the hull.
  CHECK(r["largest_gap_m"].get<double>() < 1.3 * r["even_gap_m"].get<double>());
  CHECK(r["centre_of_mass_m"][1].get<double>() == Approx(0.0).margin(1e-9));
}

TEST_CASE("mesh report: the mls skin reproduces the crash-sized affine map, idw does not", "[mesh_report]") {
  const auto car = deform::makeBuiltin("builtin:sedan?vertices=5000");
  sandbox::MeshReportOptions options;
  options.skin = {3.5, 8, 2, deform::SkinMethod::mls};
  const auto mls = sandbox::meshReport(car, options);
  options.skin.method = deform::SkinMethod::idw;
  const auto idw = sandbox::meshReport(car, options);
  CHECK(mls["skin_method"] == "mls");
  CHECK(idw["skin_method"] == "idw");
  CHECK(mls["affine_reproduction_error_max_m"].get<double>() <= 1e-5);
  CHECK(idw["affine_reproduction_error_max_m"].get<double>() > 1e-2);
  CHECK(mls["weights_sum_max_error"].get<double>() < 1e-5);
  CHECK(idw["weight_abs_max"].get<double>() <= 1.0);
  CHECK(idw["weights_negative_fraction"].get<double>() == 0.0);
  CHECK(mls["weights_negative_fraction"].get<double>() > 0.0);  // extrapolation needs negative weights
  CHECK_THAT(sandbox::formatMeshReport(mls), Catch::Contains("max affine error"));
}
