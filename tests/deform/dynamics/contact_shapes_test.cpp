// Point-in-obstacle queries: exact primitives, and libccd's MPR on a support function.
#include <catch2/catch.hpp>
#include <deform/contact_shapes.hpp>
#include <deform/error.hpp>
#include <support_wide.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace deform;

TEST_CASE("exact penetration of the primitives", "[dynamics]") {
  Penetration p;
  CHECK(penetration(HalfSpaceShape{{0, 0, 2}, 1.0}, {0, 0, 0.25}, p));  // plane z = 0.5, normal unnormalised
  CHECK(p.depth_m == Approx(0.25));
  CHECK(p.normal.z() == Approx(1.0));
  CHECK_FALSE(penetration(HalfSpaceShape{{0, 0, 1}, 0.5}, {0, 0, 0.6}, p));

  CHECK(penetration(SphereShape{{1, 0, 0}, 0.5}, {1.2, 0, 0}, p));
  CHECK(p.depth_m == Approx(0.3));
  CHECK(p.normal.x() == Approx(1.0));

  BoxShape box{
      {0, 0, 0}, Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix(), {2, 1, 1}};
  CHECK(penetration(box, {0.8, 0.1, 0.0}, p));  // box's local y is the frame's -x
  CHECK(p.depth_m == Approx(0.2));
  CHECK(p.normal.x() == Approx(1.0).margin(1e-12));

  CHECK(penetration(CapsuleShape{{0, 0, 0}, {0, 0, 2}, 0.5}, {0.1, 0, 3.0}, p) == false);
  CHECK(penetration(CapsuleShape{{0, 0, 0}, {0, 0, 2}, 0.5}, {0.4, 0, 1.0}, p));
  CHECK(p.depth_m == Approx(0.1));
}

TEST_CASE("libccd's penetration of a support-function box matches the exact box", "[dynamics]") {
  std::vector<Eigen::Vector3d> corners;
  for (double x : {-1.0, 1.0})
    for (double y : {-0.5, 0.5})
      for (double z : {-0.25, 0.25}) corners.emplace_back(x + 3.0, y, z);
  const ConvexPoints points(corners);
  const ConvexSupportShape hull = points.shape();
  const BoxShape box{{3, 0, 0}, Eigen::Matrix3d::Identity(), {1, 0.5, 0.25}};
  for (const Eigen::Vector3d& point : {Eigen::Vector3d(3.9, 0.1, 0.0), Eigen::Vector3d(3.2, 0.45, -0.1),
                                       Eigen::Vector3d(2.5, -0.1, 0.2), Eigen::Vector3d(5, 0, 0)}) {
    Penetration exact, mpr;
    const bool in_exact = penetration(box, point, exact), in_mpr = penetration(hull, point, mpr);
    INFO("point " << point.transpose());
    REQUIRE(in_exact == in_mpr);
    if (!in_exact) continue;
    CHECK(mpr.depth_m == Approx(exact.depth_m).margin(1e-6));
    CHECK((mpr.normal - exact.normal).norm() < 1e-6);
  }
}

TEST_CASE("a support shape's bounding box holds it and changes no answer, only skips the far queries",
          "[dynamics]") {
  // A car-like hull, turned: its box is its support points' extent along each axis.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.6, Eigen::Vector3d(0.2, 0.3, 1).normalized()).matrix();
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 60; ++i) {
    const double a = 2.399963 * i, z = -0.6 + 1.2 * (i + 0.5) / 60;  // a golden-angle spiral
    const double r = std::sqrt(1 - z * z / 0.36);
    points.push_back(turn * Eigen::Vector3d(2.2 * r * std::cos(a), 0.9 * r * std::sin(a), z) +
                     Eigen::Vector3d(1, 2, 0.5));
  }
  const ConvexPoints hull(points);
  const ConvexSupportShape boxed = hull.shape();
  ConvexSupportShape unboxed = boxed;
  unboxed.box_min_m.setConstant(HUGE_VAL);
  unboxed.box_max_m.setConstant(-HUGE_VAL);
  for (const Eigen::Vector3d& p : points) {
    CHECK((p.array() >= boxed.box_min_m.array()).all());
    CHECK((p.array() <= boxed.box_max_m.array()).all());
  }
  for (int k = 0; k < 3; ++k) {  // tight: some point on every face of the box
    const auto along = [k](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a[k] < b[k]; };
    CHECK(std::max_element(points.begin(), points.end(), along)->coeff(k) == boxed.box_max_m[k]);
    CHECK(std::min_element(points.begin(), points.end(), along)->coeff(k) == boxed.box_min_m[k]);
  }
  // The same answer, bit for bit, for points all around (inside, near, within the margin, far).
  int inside = 0, skipped = 0;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector3d q =
        Eigen::Vector3d(1, 2, 0.5) +
        Eigen::Vector3d(std::sin(1.1 * i) * 2.8, std::sin(2.3 * i + 1) * 2.8, std::sin(3.7 * i + 2) * 1.0);
    Penetration with, without;
    const bool in_with = penetration(boxed, q, with, 0.05),
               in_without = penetration(unboxed, q, without, 0.05);
    INFO("point " << q.transpose());
    REQUIRE(in_with == in_without);
    if (in_with) {
      CHECK(with.depth_m == without.depth_m);
      CHECK(with.normal == without.normal);
      inside += with.depth_m > 0;
    }
    const bool in_sphere = (q - boxed.centre_m).norm() <= boxed.bounding_radius_m + 0.05;
    skipped += in_sphere && outsideBox(boxed, q, q, 0.05);
  }
  CHECK(inside > 100);
  CHECK(skipped > 400);  // queries the sphere let through and the box does not
  CHECK_FALSE(outsideBox(unboxed, Eigen::Vector3d(1e9, 0, 0), Eigen::Vector3d(1e9, 0, 0), 0));  // unknown
}

TEST_CASE("bad contact shapes are refused naming the field", "[dynamics]") {
  CHECK_THROWS_WITH(checkContactShape(SphereShape{{0, 0, 0}, -1}, "contacts[0]"),
                    Catch::Contains("contacts[0].radius_m"));
  CHECK_THROWS_WITH(checkContactShape(HalfSpaceShape{{0, 0, 0}, 0}, "contacts[1]"),
                    Catch::Contains("contacts[1].normal"));
  CHECK_THROWS_AS(checkContactShape(ConvexSupportShape{}, "contacts[2]"), InputError);
  const std::vector<Eigen::Vector3d> corners{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const ConvexPoints tetrahedron(corners);
  ConvexSupportShape nan_box = tetrahedron.shape();
  nan_box.box_max_m.x() = HUGE_VAL;
  CHECK_THROWS_WITH(checkContactShape(nan_box, "contacts[3]"), Catch::Contains("contacts[3].box_max_m"));
}

TEST_CASE("within the contact margin a point outside is reported with a negative depth", "[dynamics]") {
  Penetration p;
  CHECK_FALSE(penetration(HalfSpaceShape{{0, 0, 1}, 0.0}, {0, 0, 0.005}, p));
  REQUIRE(penetration(HalfSpaceShape{{0, 0, 1}, 0.0}, {0, 0, 0.005}, p, 0.01));
  CHECK(p.depth_m == Approx(-0.005));
  REQUIRE(penetration(SphereShape{{0, 0, 0}, 1.0}, {0, 1.004, 0}, p, 0.01));
  CHECK(p.depth_m == Approx(-0.004));
  CHECK_FALSE(penetration(CapsuleShape{{0, 0, 0}, {0, 0, 1}, 0.5}, {0.52, 0, 0.5}, p, 0.01));
  // libccd: the point inflated to a ball of the margin's radius.
  std::vector<Eigen::Vector3d> corners;
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0})
      for (double z : {-1.0, 1.0}) corners.emplace_back(x, y, z);
  const ConvexPoints cube(corners);
  REQUIRE(penetration(cube.shape(), {0.2, 0.1, 1.006}, p, 0.01));
  CHECK(p.depth_m == Approx(-0.006).margin(1e-6));
  CHECK(p.normal.z() == Approx(1.0).margin(1e-6));
  CHECK_FALSE(penetration(cube.shape(), {0.2, 0.1, 1.02}, p, 0.01));
}

TEST_CASE("a post's swept cylinder: exact push-out, and its support points lie on its surface",
          "[dynamics]") {
  // A 0.1 m post from 2 m underground to 1 m up, swept 0.3 m along +x (away from a car at -x).
  const CylinderShape post{{0, 0, -2}, {0, 0, 1}, 0.1, {0.3, 0, 0.05}};  // the sweep's z is ignored
  Penetration p;
  CHECK(penetration(post, {-0.05, 0, 0.5}, p));  // in front of the axis: back toward the car
  CHECK(p.depth_m == Approx(0.05));
  CHECK(p.normal.x() == Approx(-1.0));
  CHECK(penetration(post, {0.2, 0.06, 0.5}, p));  // in the swept flank: out sideways, never through
  CHECK(p.depth_m == Approx(0.04));
  CHECK(p.normal.y() == Approx(1.0));
  CHECK(penetration(post, {0.0, 0.0, 0.97}, p));  // just under the flat top: out through it
  CHECK(p.depth_m == Approx(0.03));
  CHECK(p.normal.z() == Approx(1.0));
  CHECK_FALSE(penetration(post, {-0.12, 0, 0.5}, p));
  CHECK(penetration(post, {-0.105, 0, 1.004}, p, 0.01));  // beyond the rim, within the margin
  CHECK(p.depth_m == Approx(-std::hypot(0.005, 0.004)));
  CHECK(p.normal.x() < 0);
  CHECK(p.normal.z() > 0);
  CHECK_FALSE(penetration(post, {-0.105, 0, 1.004}, p, 0.005));

  Eigen::Vector3d centre;
  double radius = 0;
  REQUIRE(boundingSphere(post, centre, radius));
  // The swept cylinder's outline: both rims, at the post and at the sweep's end (its part across the axis).
  std::vector<Eigen::Vector3d> outline;
  for (int k = 0; k < 64; ++k)
    for (const double z : {-2.0, 1.0})
      for (const double sweep_x : {0.0, 0.3}) {
        const double angle = 2 * M_PI * k / 64;
        outline.emplace_back(sweep_x + 0.1 * std::cos(angle), 0.1 * std::sin(angle), z);
      }
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d direction(std::cos(0.7 * k) * std::sin(0.31 * k + 0.2),
                                    std::sin(0.7 * k) * std::sin(0.31 * k + 0.2), std::cos(0.31 * k + 0.2));
    Eigen::Vector3d support;
    REQUIRE(supportPoint(post, direction, support));
    INFO("direction " << direction.transpose() << ", support " << support.transpose());
    CHECK((support - centre).norm() <= radius + 1e-12);
    REQUIRE(penetration(post, support, p, 1e-9));  // on the surface
    CHECK(std::abs(p.depth_m) < 1e-9);
    double furthest = -1e300;  // no point of the outline lies further along the direction
    for (const Eigen::Vector3d& q : outline) furthest = std::max(furthest, direction.dot(q));
    CHECK(direction.dot(support) >= furthest - 1e-12);
  }
}

TEST_CASE("a point the cheap test calls apart is never within the margin, and most far points are",
          "[dynamics]") {
  const double margin_m = 0.01;
  const BoxShape box{{0.3, -0.2, 0.1},
                     Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
                     {0.4, 0.2, 0.3}};
  const std::vector<ContactShape> shapes = {
      HalfSpaceShape{{0.3, -1.2, 2.0}, 0.4},  // normal not unit
      SphereShape{{0.1, 0.2, -0.3}, 0.35},
      box,
      CapsuleShape{{0, 0, -0.5}, {0.2, 0.1, 0.6}, 0.08},
      CylinderShape{{0.1, 0, -1}, {0.1, 0, 1}, 0.08, {0.3, 0.1, 0}},
  };
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    INFO("shape " << k);
    const SurelyApart apart(shapes[k], margin_m);
    Penetration p;
    int far = 0, called_apart = 0, near_edge = 0;
    for (int trial = 0; trial < 20000; ++trial) {
      const Eigen::Vector3d x(u(random), u(random), u(random));
      const bool within = penetration(shapes[k], x, p, margin_m);
      if (apart(x)) {
        ++called_apart;
        REQUIRE_FALSE(within);
      }
      if (within) {
        // Pushed out along the contact normal to just inside the margin, and to just beyond it.
        const Eigen::Vector3d normal = p.normal;
        const double depth_m = p.depth_m;
        const Eigen::Vector3d just_within = x + (depth_m + 0.999 * margin_m) * normal;
        if (penetration(shapes[k], just_within, p, margin_m)) REQUIRE_FALSE(apart(just_within));
        near_edge += apart(x + (depth_m + 1.0001 * margin_m) * normal);
      } else {
        ++far;
      }
    }
    // Useful: it rejects at least half the points outside (a plane's far side, and the space outside a
    // primitive's sphere).
    CHECK(called_apart > far / 2);
    if (k == 0) CHECK(near_edge > 0);  // the plane's test is tight
  }
  // A box's corner: its test reaches out along every axis at once, sqrt(3) margins along the diagonal.
  const Eigen::Vector3d corner =
      box.centre_m + box.axes * (box.half_extents_m + 0.9 * margin_m * Eigen::Vector3d::Ones());
  Penetration p;
  CHECK(penetration(box, corner, p, margin_m));
  CHECK_FALSE(SurelyApart(box, margin_m)(corner));
  // Axes a float rotation left off unit length by 4e-8, margin 0: a point a hair inside each corner (as
  // the box's own test measures) is not called apart.
  BoxShape rounded;
  rounded.half_extents_m = {1, 1, 1};
  rounded.axes =
      Eigen::AngleAxisf(0.7f, Eigen::Vector3f(1, 2, 3).normalized()).toRotationMatrix().cast<double>();
  const Eigen::Matrix3d to_frame = rounded.axes.transpose().inverse();
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d local((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    const Eigen::Vector3d x = to_frame * (local * (1 - 1e-12));
    REQUIRE(penetration(rounded, x, p, 0.0));
    CHECK_FALSE(SurelyApart(rounded, 0.0)(x));
  }
  // Sheared axes hold points far outside the circumsphere: such a box is never called apart.
  BoxShape sheared;
  sheared.half_extents_m = {0.5, 0.5, 0.5};
  sheared.axes.col(1) = Eigen::Vector3d(std::cos(0.1), std::sin(0.1), 0);
  REQUIRE(penetration(sheared, {0, 4, 0}, p, margin_m));
  CHECK_FALSE(SurelyApart(sheared, margin_m)({0, 4, 0}));
  // A support shape is never called apart (its bounding radius is not checked).
  const ConvexPoints hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  CHECK_FALSE(SurelyApart(hull.shape(), margin_m)({10, 10, 10}));
}

TEST_CASE("a shape called Lipschitz reports a depth that moves no faster than the point", "[dynamics]") {
  // findFaceContacts skips the samples nearer a triangle's centroid than the centroid's distance less the
  // margin: sound only where |depth(x) - depth(y)| <= |x - y| wherever both are reported.
  const Eigen::Matrix3d turned =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const std::vector<ContactShape> lipschitz = {
      SphereShape{{0.2, 0, 0}, 0.5},
      CapsuleShape{{0, 0, -1}, {0, 0, 1}, 0.3},
      CylinderShape{{0, 0, -2}, {0, 0, 1}, 0.127, {0.4, 0.1, 0}},
      BoxShape{{0, 0.1, 0}, turned, {0.5, 0.25, 0.4}},
  };
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5), step(-0.05, 0.05);
  constexpr double kReach = 10.0;  // every point within reach is reported
  for (const ContactShape& shape : lipschitz) {
    CHECK(distanceIsLipschitz(shape));
    double steepest = 0;
    for (int k = 0; k < 20000; ++k) {
      const Eigen::Vector3d x(coordinate(random), coordinate(random), coordinate(random));
      const Eigen::Vector3d y = x + Eigen::Vector3d(step(random), step(random), step(random));
      Penetration px, py;
      REQUIRE(penetration(shape, x, px, kReach));
      REQUIRE(penetration(shape, y, py, kReach));
      steepest = std::max(steepest, std::abs(px.depth_m - py.depth_m) / (x - y).norm());
    }
    CHECK(steepest <= 1 + 1e-9);
    CHECK(steepest > 0.9);  // the bound is reached: the depth is a distance, not a fraction of one
  }
  // Not claimed: a half-space (unbounded, tested by its plane), a support shape (MPR's depth), a box whose
  // axes are not orthonormal (its face-pair distances are scaled).
  CHECK_FALSE(distanceIsLipschitz(HalfSpaceShape{{0, 0, 1}, 0}));
  CHECK_FALSE(distanceIsLipschitz(ConvexSupportShape{}));
  CHECK_FALSE(distanceIsLipschitz(BoxShape{{0, 0, 0}, 2.0 * Eigen::Matrix3d::Identity(), {1, 1, 1}}));
}

TEST_CASE("a point set's support four at a time is the one-by-one scan's point, ties and all", "[dynamics]") {
  // Random sets of 1 to 41 points (n mod 4 all four ways, fewer than the wide path takes); some sets of
  // few distinct points repeated, so that ties are common, and directions along the axes, where points
  // of a box tie by construction.
  std::mt19937 random(23);
  std::uniform_real_distribution<double> u(-2, 2);
  std::uniform_int_distribution<int> count(1, 41);
  std::size_t wide_differs = 0, ties = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const std::size_t n = static_cast<std::size_t>(count(random));
    std::vector<Eigen::Vector3d> points;
    if (trial % 3 == 0) {
      for (std::size_t i = 0; i < n; ++i)  // corners of a unit box: many equal products
        points.emplace_back(random() % 2, random() % 2, random() % 2);
    } else {
      for (std::size_t i = 0; i < n; ++i) points.emplace_back(u(random), u(random), u(random));
    }
    const Eigen::Vector3d direction =
        trial % 2 == 0 ? Eigen::Vector3d::Unit(trial % 3) : Eigen::Vector3d(u(random), u(random), u(random));
    const std::size_t one = farthestAlong(points.data(), n, direction, false);
    const std::size_t four = farthestAlong(points.data(), n, direction, true);
    // The scan's answer: the first point of largest product.
    double largest = -HUGE_VAL;
    for (const auto& p : points) largest = std::max(largest, p.dot(direction));
    std::size_t first = 0;
    while (points[first].dot(direction) < largest) ++first;
    std::size_t at_largest = 0;
    for (const auto& p : points) at_largest += p.dot(direction) == largest;
    ties += at_largest > 1;
    REQUIRE(one == first);
    wide_differs += four != one;
  }
  CHECK(wide_differs == 0);
  CHECK(ties > 1000);
  // A direction whose products are not finite: the one-by-one scan's answer too.
  std::vector<Eigen::Vector3d> points(13, Eigen::Vector3d(1, 2, 3));
  points[5] = {4, 5, 6};
  const Eigen::Vector3d nan(std::nan(""), 0, 0);
  CHECK(farthestAlong(points.data(), points.size(), nan, true) ==
        farthestAlong(points.data(), points.size(), nan, false));
}

TEST_CASE("the points near a shape, listed four at a time, are those the one-by-one test keeps",
          "[dynamics]") {
  // The two kinds the wide test takes: a plane, and a ball (sphere, capsule); ranges that start and end off
  // a multiple of four. (A shape it is unsure of lists every point, one at a time either way.)
  const std::vector<ContactShape> shapes = {
      HalfSpaceShape{{0.3, -1.2, 2.0}, 0.4},
      SphereShape{{0.1, 0.2, -0.3}, 0.6},
      CapsuleShape{{0, 0, -0.5}, {0.2, 0.1, 0.6}, 0.3},
  };
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<Eigen::Vector3d> points(1003);
  for (auto& p : points) p = {u(random), u(random), u(random)};
  for (const ContactShape& shape : shapes) {
    const SurelyApart apart(shape, 0.01);
    for (const std::size_t begin : {std::size_t{0}, std::size_t{3}})
      for (const std::size_t end : {std::size_t{1003}, std::size_t{998}}) {
        std::vector<uint32_t> one, four, expected;
        apart.listNear(points.data(), begin, end, false, one);
        apart.listNear(points.data(), begin, end, true, four);
        for (std::size_t i = begin; i < end; ++i)
          if (!apart(points[i])) expected.push_back(static_cast<uint32_t>(i));
        REQUIRE(one == expected);
        REQUIRE(four == expected);
        // Both kinds of answer occur.
        CHECK(expected.size() > 10);
        CHECK(expected.size() + 10 < end - begin);
      }
  }
}
