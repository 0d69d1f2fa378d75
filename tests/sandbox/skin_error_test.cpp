// tradeoff --skin-only: the skin measured alone on known fields obeys what each method guarantees.
#include <tradeoff/known_fields.hpp>
#include <tradeoff/skin_error.hpp>
#include <tradeoff/skin_error_report.hpp>

#include <catch2/catch.hpp>

namespace {

const sandbox::SkinErrorRow& row(const std::vector<sandbox::SkinErrorRow>& rows, const std::string& field,
                                 const std::string& method, std::size_t n) {
  const sandbox::SkinErrorRow* r = sandbox::findSkinErrorRow(rows, field, method, n, 8, 3.5);
  REQUIRE(r != nullptr);
  return *r;
}

}  // namespace

TEST_CASE("known fields: the bend lifts the ends 0.1 m, the twist turns the ends 10 degrees apart",
          "[tradeoff][skin_error]") {
  deform::Aabb box;
  box.min_m = {-2, -0.9, 0};
  box.max_m = {2, 0.9, 1.4};
  const Eigen::Vector3d centre(0, 0, 0.7);
  CHECK(sandbox::bendField(box).displacement_m({2, 0, 0.7}).z() == Approx(0.1));
  CHECK(sandbox::bendField(box).displacement_m(centre).norm() == Approx(0).margin(1e-15));
  // A point 1 m off the axis at each end turns by +-5 degrees: 2 sin(5 deg) apart in the turned plane.
  const Eigen::Vector3d front =
      Eigen::Vector3d(2, 1, 0.7) + sandbox::twistField(box).displacement_m({2, 1, 0.7});
  const Eigen::Vector3d rear =
      Eigen::Vector3d(-2, 1, 0.7) + sandbox::twistField(box).displacement_m({-2, 1, 0.7});
  CHECK((front - rear).tail<2>().norm() == Approx(2 * std::sin(5 * 3.14159265358979 / 180)));
  // The crush pushes the bumper back 0.5 m and nothing 1.5 m behind it.
  CHECK(sandbox::crushField(box).displacement_m({2, 0, 0.5}).x() == Approx(-0.5));
  CHECK(sandbox::crushField(box).displacement_m({0.5, 0.9, 0.5}).norm() == Approx(0).margin(1e-15));
}

TEST_CASE(
    "skin error: mls reproduces an affine motion, both skins improve with N on the bend, mls beats idw "
    "at N = 60",
    "[tradeoff][skin_error]") {
  sandbox::SkinErrorOptions options;
  options.control_points = {60, 250};
  options.k = {8};
  options.alpha = {3.5};
  const auto rows = sandbox::runSkinError(options);
  REQUIRE(rows.size() == 2 * 3 * 5);  // N x method (idw, mls, spline) x field
  for (const auto& r : rows) {
    INFO(r.field << " " << r.method << " N=" << r.control_points);
    CHECK(r.max_error_m < r.field_max_m + 0.5);  // a skin error is within the motion's size
  }
  // Linear precision (Schaefer et al. 2006): float rounding only.
  CHECK(row(rows, "affine", "mls", 60).max_error_m < 1e-5);
  CHECK(row(rows, "affine", "mls", 250).max_error_m < 1e-5);
  // idw reproduces translations only: an affine motion leaves mm of error.
  CHECK(row(rows, "affine", "idw", 60).rms_error_m > 1e-3);
  // Finer control meshes sample the bend better.
  CHECK(row(rows, "bend", "idw", 250).rms_error_m < row(rows, "bend", "idw", 60).rms_error_m);
  CHECK(row(rows, "bend", "mls", 250).rms_error_m < row(rows, "bend", "mls", 60).rms_error_m);
  CHECK(row(rows, "bend", "mls", 60).rms_error_m < row(rows, "bend", "idw", 60).rms_error_m);
  // The crash's own dent: a real dent (the finest model's front goes back more than 0.3 m), which both
  // skins sample better at 250 points than at 60.
  CHECK(row(rows, "wall_crash", "idw", 60).field_max_m > 0.3);
  CHECK(row(rows, "wall_crash", "idw", 250).rms_error_m < row(rows, "wall_crash", "idw", 60).rms_error_m);
  CHECK(row(rows, "wall_crash", "mls", 250).rms_error_m < row(rows, "wall_crash", "mls", 60).rms_error_m);
  // The spline (every point on every vertex): linear precision too, and half idw's RMS error or less at
  // 60 points on every field, the real crash's dent included (measured 0.49 on crush, 0.47 on
  // wall_crash; mls 0.67 and 0.80).
  const auto spline = [&](const std::string& field, std::size_t n) -> const sandbox::SkinErrorRow& {
    const sandbox::SkinErrorRow* r = sandbox::findSkinErrorRow(rows, field, "spline", n, 0, 0.0);
    REQUIRE(r != nullptr);
    return *r;
  };
  CHECK(spline("affine", 60).max_error_m < 1e-5);
  CHECK(spline("affine", 250).max_error_m < 1e-5);
  for (const char* field : {"bend", "twist", "crush", "wall_crash"}) {
    INFO(field);
    CHECK(spline(field, 60).rms_error_m <= 0.5 * row(rows, field, "idw", 60).rms_error_m);
    CHECK(spline(field, 250).rms_error_m < spline(field, 60).rms_error_m);
  }
  // The report names the target and every field.
  const std::string md = sandbox::skinErrorMarkdown(rows, "test");
  for (const char* field : {"bend", "twist", "crush", "affine", "wall_crash"})
    CHECK(md.find(field) != std::string::npos);
}
