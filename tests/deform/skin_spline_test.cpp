// The spline skin (cubic polyharmonic spline with a linear part through every control point, evaluated at
// a lattice's nodes and carried to the vertices by quadratic B-splines): affine maps exact, partition of
// unity, a vertex on a control point follows it, smooth across cells where idw kinks, and the inputs it
// cannot take refused by name.
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/error.hpp>
#include <deform/mesh.hpp>
#include <deform/skin.hpp>
#include <deform/skin_checks.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "skin_fixtures.hpp"

namespace {

using skin_test::Sedan;

using deform::SkinMethod;

deform::Skin spline(const std::vector<Eigen::Vector3f>& vertices, const std::vector<Eigen::Vector3d>& control,
                    deform::SkinLayout layout = deform::SkinLayout::compact) {
  deform::SkinOptions options;
  options.method = SkinMethod::spline;
  options.threads = 2;
  options.layout = layout;
  return deform::Skin::build(vertices, control, options);
}

}  // namespace

TEST_CASE("spline: 27 lattice nodes on every vertex, weights summing to one", "[skin][spline]") {
  Sedan s;
  for (const deform::SkinLayout layout : {deform::SkinLayout::compact, deform::SkinLayout::float_weights}) {
    const deform::Skin skin = spline(s.car.body.positions_m, s.control, layout);
    CHECK(skin.method() == SkinMethod::spline);
    REQUIRE(skin.influences() == 27);  // 3 x 3 x 3 lattice nodes, whatever k_nearest says
    CHECK(skin.latticeNodeCount() > 1000);
    double worst = 0;
    bool finite = true;
    for (std::size_t j = 0; j < skin.vertexCount(); ++j) {
      double sum = 0;
      for (std::size_t k = 0; k < skin.influences(); ++k) {
        finite = finite && std::isfinite(skin.slotWeight(j, k));
        sum += skin.slotWeight(j, k);
      }
      worst = std::max(worst, std::abs(sum - 1.0));
    }
    CHECK(finite);
    CAPTURE(static_cast<int>(layout), worst);
    CHECK(worst < 1e-5);
    if (skin.fixedPointWeights())  // the integers of each vertex sum exactly to the scale
      for (std::size_t j = 0; j < skin.vertexCount(); j += 97) {
        int64_t sum = 0;
        for (std::size_t k = 0; k < skin.influences(); ++k) sum += skin.slotWeightFixed(j, k);
        CHECK(sum == skin.weightScale());
      }
  }
}

TEST_CASE("spline reproduces a crash-sized affine map of the control points on the sedan", "[skin][spline]") {
  for (const std::size_t points : {60u, 250u}) {
    Sedan s(20000, points);
    const deform::AffineMap map = deform::crashSizedAffineMap(s.centre_m);
    const deform::Skin skin = spline(s.car.body.positions_m, s.control);
    const double error_m =
        deform::affineReproductionErrorMax(skin, s.car.body.positions_m, s.control, map, 2);
    CAPTURE(points, error_m);
    CHECK(error_m < 1e-5);
  }
}

TEST_CASE("spline: a vertex on a control point follows it; between points and cells it blends smoothly",
          "[skin][spline]") {
  Sedan s;
  // Vertices on three control points, and a line of vertices across the car's front at the bumper's height.
  std::vector<Eigen::Vector3f> vertices = {s.control[3].cast<float>(), s.control[17].cast<float>(),
                                           s.control[42].cast<float>()};
  const deform::Aabb box = deform::boundingBox(s.car.body);
  const int line = 200;
  for (int i = 0; i <= line; ++i) {
    const double y = box.min_m.y() + (box.max_m.y() - box.min_m.y()) * i / line;
    vertices.emplace_back(static_cast<float>(box.max_m.x() - 0.1), static_cast<float>(y),
                          static_cast<float>(box.min_m.z() + 0.4 * (box.max_m.z() - box.min_m.z())));
  }
  const deform::Skin skin = spline(vertices, s.control);
  // A smooth dent: the front pushed back by up to 0.4 m, more in the middle.
  std::vector<Eigen::Vector3d> displacement(s.control.size());
  for (std::size_t i = 0; i < s.control.size(); ++i) {
    const double front = std::max(0.0, s.control[i].x() - (box.max_m.x() - 1.0));
    displacement[i] = {-0.4 * front * std::cos(s.control[i].y()), 0.05 * s.control[i].y(), 0};
  }
  std::vector<Eigen::Vector3f> out(vertices.size());
  skin.deform(vertices.data(), displacement.data(), out.data(), 2);
  const std::size_t on[] = {3, 17, 42};
  for (std::size_t v = 0; v < 3; ++v) {
    const Eigen::Vector3f expected = vertices[v] + displacement[on[v]].cast<float>();
    CAPTURE(v, (out[v] - expected).norm());
    // The spline interpolates; the lattice's B-spline smooths it between nodes 0.19 m apart: within a
    // millimetre of the point under a 0.4 m dent (measured 0.15-0.45 mm).
    CHECK((out[v] - expected).norm() < 1e-3f);
  }
  // No crease along the line: the second differences of the skinned motion between neighbouring
  // vertices 9 mm apart stay within those of the field itself evaluated at the vertices (its own
  // curvature), where a kink where the nearest points change would stand out (idw at K = 8, measured).
  const auto field = [&](const Eigen::Vector3f& v) {
    const double front = std::max(0.0, static_cast<double>(v.x()) - (box.max_m.x() - 1.0));
    return Eigen::Vector3d(-0.4 * front * std::cos(v.y()), 0.05 * v.y(), 0);
  };
  const auto largestSecondDifference = [&](const std::vector<Eigen::Vector3f>& moved, bool exact) {
    double largest_m = 0;
    for (std::size_t v = 4; v + 1 < vertices.size(); ++v) {
      Eigen::Vector3d d[3];
      for (int i = 0; i < 3; ++i) {
        const std::size_t w = v - 1 + static_cast<std::size_t>(i);
        d[i] = exact ? field(vertices[w]) : (moved[w] - vertices[w]).cast<double>();
      }
      largest_m = std::max(largest_m, (d[0] - 2 * d[1] + d[2]).norm());
    }
    return largest_m;
  };
  const auto idw = deform::Skin::build(vertices, s.control, {3.5, 8, 2, SkinMethod::idw});
  std::vector<Eigen::Vector3f> idw_out(vertices.size());
  idw.deform(vertices.data(), displacement.data(), idw_out.data(), 2);
  const double spline_m = largestSecondDifference(out, false), exact_m = largestSecondDifference(out, true),
               idw_m = largestSecondDifference(idw_out, false);
  CAPTURE(spline_m, exact_m, idw_m);
  CHECK(spline_m < 1.5 * exact_m);
  CHECK(idw_m > 3 * exact_m);
}

TEST_CASE("spline refuses more control points than its dense system allows, and flat control points",
          "[skin][spline]") {
  const std::vector<Eigen::Vector3f> vertices = {{0.1f, 0.2f, 0.0f}};
  std::vector<Eigen::Vector3d> many;
  for (std::size_t i = 0; i <= deform::kSplineMostControlPoints; ++i) {
    const double t = static_cast<double>(i);
    many.emplace_back(std::cos(0.1 * t), std::sin(0.37 * t), 0.01 * t);
  }
  CHECK_THROWS_WITH(spline(vertices, many), Catch::Contains("at most 256 control points"));
  std::vector<Eigen::Vector3d> flat;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) flat.emplace_back(i, j, 0.0);
  CHECK_THROWS_WITH(spline(vertices, flat), Catch::Contains("span three dimensions"));
}

TEST_CASE("spline: the same bits on any thread count, and a partial update is a full one or none",
          "[skin][spline]") {
  Sedan s;
  const deform::Skin skin = spline(s.car.body.positions_m, s.control);
  std::vector<Eigen::Vector3d> displacement(s.control.size());
  for (std::size_t i = 0; i < displacement.size(); ++i)
    displacement[i] = {-0.3 * std::sin(static_cast<double>(i)), 0.05,
                       0.02 * std::cos(static_cast<double>(i))};
  const auto& rest = s.car.body.positions_m;
  std::vector<Eigen::Vector3f> one(rest.size()), two(rest.size()), partial(rest);
  skin.deform(rest.data(), displacement.data(), one.data(), 1);
  skin.deform(rest.data(), displacement.data(), two.data(), 2);
  CHECK(one == two);
  // Nothing moved: nothing recomputed. One point moved: the spline moves every node, so every vertex.
  std::vector<uint8_t> moved(s.control.size(), 0), recomputed;
  CHECK(skin.deformMoved(rest.data(), displacement.data(), moved, partial.data(), 2, &recomputed) == 0);
  CHECK(partial == rest);
  moved[5] = 2;  // any non-zero flag counts, as the sparse skins read it
  CHECK(skin.deformMoved(rest.data(), displacement.data(), moved, partial.data(), 2, &recomputed) ==
        rest.size());
  CHECK(partial == one);
  CHECK(std::count(recomputed.begin(), recomputed.end(), uint8_t{1}) == static_cast<long>(rest.size()));
  // The weight of a control point on a vertex is the spline's through the lattice: they sum to one.
  double sum = 0;
  for (uint32_t i = 0; i < s.control.size(); ++i) sum += skin.weight(123, i);
  CHECK(sum == Approx(1.0).margin(1e-5));
  CHECK_FALSE(skin.nonnegativeWeights());
  // The gain bounds every vertex's motion: |v - v0| <= gain x the largest control-point displacement.
  double largest_m = 0, worst_ratio = 0;
  for (const auto& d : displacement) largest_m = std::max(largest_m, d.norm());
  for (std::size_t j = 0; j < rest.size(); ++j)
    worst_ratio = std::max(worst_ratio, static_cast<double>((one[j] - rest[j]).norm()) / largest_m);
  CAPTURE(worst_ratio, skin.displacementGain());
  CHECK(worst_ratio <= skin.displacementGain());
  CHECK(skin.displacementGain() < 10);  // over the nodes vertices follow (6.4 at 60 points), not all
}
