#include <deform/error.hpp>
#include <deform/skin.hpp>

#include <catch2/catch.hpp>
#include <cmath>

#include "point_sets.hpp"
#include "skin_fixtures.hpp"

namespace {

using skin_test::largestWeightSumError;

std::vector<Eigen::Vector3f> toFloat(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : points) out.push_back(p.cast<float>());
  return out;
}

struct Fixture {
  std::vector<Eigen::Vector3d> control = test_points::sphere(60, {2.4, 0.9, 0.7});
  // Vertices inside and on a slightly smaller ellipsoid, like a body inside its hull.
  std::vector<Eigen::Vector3f> vertices = toFloat(test_points::sphere(5000, {2.3, 0.85, 0.65}));
  Fixture() {
    for (const auto& p : test_points::cloud(3000, 11))
      vertices.push_back(Eigen::Vector3f(3.0f * float(p.x()), float(p.y()), float(p.z())));
  }
  std::vector<Eigen::Vector3f> deformed(const deform::Skin& skin,
                                        const std::vector<Eigen::Vector3d>& displacement,
                                        unsigned threads = 1) const {
    std::vector<Eigen::Vector3f> out(vertices.size());
    skin.deform(vertices.data(), displacement.data(), out.data(), threads);
    return out;
  }
};

}  // namespace

TEST_CASE("weights sum to one for every vertex, dense and sparse", "[skin]") {
  Fixture f;
  for (std::size_t k : {0u, 1u, 4u, 8u, 16u}) {
    for (double alpha : {0.5, 1.0, 3.5, 16.0}) {
      CAPTURE(k, alpha);
      auto skin = deform::Skin::build(f.vertices, f.control, {alpha, k, 2});
      CHECK(skin.influences() == (k == 0 ? 60 : k));
      CHECK(largestWeightSumError(skin) < 1e-6);
    }
  }
}

TEST_CASE("moving every control point by t moves every vertex by exactly t", "[skin]") {
  Fixture f;
  const Eigen::Vector3d t(0.31, -0.12, 0.05);
  std::vector<Eigen::Vector3d> displacement(f.control.size(), t);
  for (std::size_t k : {0u, 4u, 8u, 16u}) {
    auto skin = deform::Skin::build(f.vertices, f.control, {3.5, k, 2});
    auto out = f.deformed(skin, displacement);
    double worst_m = 0;
    for (std::size_t j = 0; j < out.size(); ++j)
      worst_m = std::max(worst_m, (out[j] - f.vertices[j] - t.cast<float>()).cast<double>().norm());
    CHECK(worst_m < 2e-6);  // float arithmetic on coordinates of a few metres
  }
}

TEST_CASE("K equal to the number of control points reproduces dense weights", "[skin]") {
  Fixture f;
  auto dense = deform::Skin::build(f.vertices, f.control, {3.5, 0, 2});
  auto all = deform::Skin::build(f.vertices, f.control, {3.5, f.control.size(), 2});
  double worst = 0;
  for (std::size_t j = 0; j < f.vertices.size(); ++j)
    for (uint32_t i = 0; i < f.control.size(); ++i)
      worst = std::max(worst, double(std::abs(dense.weight(j, i) - all.weight(j, i))));
  CHECK(worst == 0.0);
}

TEST_CASE("a higher alpha gives more local influence", "[skin]") {
  // Measured as the weight the nearest control point holds, averaged over the vertices: 1/N for alpha -> 0,
  // 1 for alpha -> infinity.
  Fixture f;
  double previous = 0;
  for (double alpha : {1.0, 2.0, 3.0, 4.0, 5.0, 8.0}) {
    auto skin = deform::Skin::build(f.vertices, f.control, {alpha, 0, 2});
    double mean_nearest = 0;
    for (std::size_t j = 0; j < skin.vertexCount(); ++j) {
      float best = 0;
      for (std::size_t k = 0; k < skin.influences(); ++k) best = std::max(best, skin.slotWeight(j, k));
      mean_nearest += best;
    }
    mean_nearest /= double(skin.vertexCount());
    CAPTURE(alpha, mean_nearest);
    CHECK(mean_nearest > previous);
    previous = mean_nearest;
  }
  CHECK(previous > 0.5);
}

TEST_CASE("a vertex on a control point follows that point exactly, at any alpha", "[skin]") {
  Fixture f;
  std::vector<Eigen::Vector3f> on_points;
  for (const auto& c : f.control) on_points.push_back(c.cast<float>());
  // The float copy of a control point is not the double point: use control points that are exact floats.
  std::vector<Eigen::Vector3d> control;
  for (const auto& v : on_points) control.push_back(v.cast<double>());
  for (double alpha : {0.5, 3.5, 16.0}) {
    for (std::size_t k : {0u, 8u}) {
      auto skin = deform::Skin::build(on_points, control, {alpha, k, 1});
      std::vector<Eigen::Vector3d> displacement(control.size(), Eigen::Vector3d::Zero());
      displacement[7] = {0.2, -0.1, 0.05};
      std::vector<Eigen::Vector3f> out(on_points.size());
      skin.deform(on_points.data(), displacement.data(), out.data(), 1);
      CHECK(skin.weight(7, 7) == 1.0f);
      CHECK(out[7] == Eigen::Vector3f(on_points[7] + displacement[7].cast<float>()));
      CHECK((out[8] - on_points[8]).norm() == 0.0f);
    }
  }
}

TEST_CASE("extreme alpha and near-coincident vertices give finite weights", "[skin]") {
  Fixture f;
  auto vertices = f.vertices;
  vertices.push_back(f.control[3].cast<float>() + Eigen::Vector3f(1e-7f, 0, 0));
  vertices.push_back(Eigen::Vector3f(1e4f, 1e4f, 1e4f));  // far away: every distance large
  for (double alpha : {0.5, 16.0, 64.0}) {
    auto skin = deform::Skin::build(vertices, f.control, {alpha, 8, 2});
    for (std::size_t j = 0; j < skin.vertexCount(); ++j)
      for (std::size_t k = 0; k < skin.influences(); ++k) REQUIRE(std::isfinite(skin.slotWeight(j, k)));
    CHECK(largestWeightSumError(skin) < 1e-6);
  }
}

TEST_CASE("the deform pass gives the same result with any thread count", "[skin]") {
  Fixture f;
  std::vector<Eigen::Vector3d> displacement;
  for (std::size_t i = 0; i < f.control.size(); ++i)
    displacement.emplace_back(0.01 * double(i % 7), -0.02 * double(i % 5), 0.003 * double(i));
  for (std::size_t k : {0u, 5u, 8u}) {
    auto one = deform::Skin::build(f.vertices, f.control, {3.5, k, 1});
    auto three = deform::Skin::build(f.vertices, f.control, {3.5, k, 3});
    REQUIRE(one.weight(100, one.slotIndex(100, 0)) == three.weight(100, three.slotIndex(100, 0)));
    auto a = f.deformed(one, displacement, 1);
    for (unsigned threads : {2u, 3u, 7u}) CHECK(f.deformed(three, displacement, threads) == a);
  }
}

TEST_CASE("bad skin options are refused", "[skin]") {
  Fixture f;
  CHECK_THROWS_AS(deform::Skin::build(f.vertices, f.control, {0.0, 8, 1}), deform::InputError);
  CHECK_THROWS_AS(deform::Skin::build(f.vertices, f.control, {-2.0, 8, 1}), deform::InputError);
  CHECK_THROWS_AS(deform::Skin::build(f.vertices, {}, {3.5, 8, 1}), deform::InputError);
}

TEST_CASE("the K nearest found through the tree are the brute-force K nearest", "[skin]") {
  const auto control = test_points::sphere(700, {2.4, 0.9, 0.7});
  std::vector<Eigen::Vector3f> vertices;
  for (const auto& p : test_points::cloud(4000, 5))
    vertices.push_back(Eigen::Vector3f(5.0f * float(p.x()), 2.0f * float(p.y()), 1.5f * float(p.z())));
  for (const auto& c : control) vertices.push_back(c.cast<float>());  // exact ties between neighbours
  const std::size_t K = 8;
  auto skin = deform::Skin::build(vertices, control, {3.5, K, 2});
  std::size_t mismatches = 0;
  for (std::size_t j = 0; j < vertices.size(); ++j) {
    std::vector<std::pair<double, uint32_t>> all;
    const Eigen::Vector3d v = vertices[j].cast<double>();
    for (uint32_t i = 0; i < control.size(); ++i) all.push_back({(control[i] - v).squaredNorm(), i});
    std::sort(all.begin(), all.end());
    std::vector<uint32_t> expected, got;
    for (std::size_t k = 0; k < K; ++k) expected.push_back(all[k].second);
    for (std::size_t k = 0; k < K; ++k) got.push_back(skin.slotIndex(j, k));
    std::sort(expected.begin(), expected.end());
    mismatches += (expected != got);
  }
  CHECK(mismatches == 0);
}

TEST_CASE("a partial update recomputes only influenced vertices and equals a full deform", "[skin]") {
  Fixture f;
  auto skin = deform::Skin::build(f.vertices, f.control, {3.5, 8, 2});
  std::vector<Eigen::Vector3d> before(f.control.size(), Eigen::Vector3d(0.01, 0, 0));
  auto out = f.deformed(skin, before, 2);
  std::vector<Eigen::Vector3d> after = before;
  std::vector<uint8_t> moved(f.control.size(), 0);
  for (std::size_t i : {3u, 17u, 40u}) {
    after[i] += Eigen::Vector3d(-0.1, 0.05, 0.2);
    moved[i] = 1;
  }
  std::size_t recomputed = skin.deformMoved(f.vertices.data(), after.data(), moved, out.data(), 2);
  CHECK(out == f.deformed(skin, after, 1));
  // Exactly the vertices with a moved point among their influences are recomputed.
  std::size_t influenced = 0;
  for (std::size_t j = 0; j < skin.vertexCount(); ++j) {
    bool any = false;
    for (std::size_t k = 0; k < skin.influences(); ++k)
      any |= moved[skin.slotIndex(j, k)] && skin.slotWeight(j, k) != 0;
    influenced += any;
  }
  CHECK(recomputed == influenced);
  CHECK(recomputed < f.vertices.size() / 2);  // 3 of 60 points with K = 8: about 3 * 8 / 60 of the mesh
  std::vector<uint8_t> none(f.control.size(), 0);
  CHECK(skin.deformMoved(f.vertices.data(), after.data(), none, out.data(), 2) == 0);
}
