// The grid that finds the wheels' ray candidates and the collision pass's pairs (vehicle/src/geom_grid.hpp)
// against the brute force it replaced: every pair of boxes, every box against the ray's.
#include "geom_grid.hpp"
#include "broad_phase.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

namespace {

bool overlap(const std::array<dReal, 6>& a, const std::array<dReal, 6>& b) {
  return !(a[0] > b[1] || a[1] < b[0] || a[2] > b[3] || a[3] < b[2] || a[4] > b[5] || a[5] < b[4]);
}

}  // namespace

TEST_CASE("Geom grid: its pairs and ray candidates are the brute force's, in the space's order") {
  dInitODE2(0);
  dSpaceID space = dSimpleSpaceCreate(nullptr);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> place(-80.0, 80.0), size(0.2, 5.0);
  dCreatePlane(space, 0, 0, 1, 0);
  for (int k = 0; k < 300; ++k) {  // cars' boxes and posts, a few long walls crossing many cells
    const bool wall = k % 50 == 0;
    dGeomID box = dCreateBox(space, wall ? 120.0 : size(random), size(random), size(random));
    dGeomSetPosition(box, place(random), place(random), size(random));
  }
  vehicle::ode::GeomGrid grid;
  grid.build(space);
  const int count = dSpaceGetNumGeoms(space);

  std::vector<uint64_t> pairs;
  grid.pairs(pairs);
  CHECK(std::is_sorted(pairs.begin(), pairs.end()));
  std::vector<uint64_t> found, expected;
  for (const uint64_t p : pairs) {
    const int i = static_cast<int>(p >> 32), j = static_cast<int>(p & 0xffffffffu);
    REQUIRE(i < j);
    if (overlap(grid.box(i), grid.box(j))) found.push_back(p);
  }
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j)
      if (overlap(grid.box(i), grid.box(j)))
        expected.push_back((static_cast<uint64_t>(i) << 32) | static_cast<uint64_t>(j));
  CHECK(expected.size() > 300);  // the plane meets every box, and some boxes meet each other
  CHECK(found == expected);
  CHECK(pairs.size() < static_cast<std::size_t>(count) * static_cast<std::size_t>(count - 1) / 8);

  std::vector<int> candidates;
  std::uniform_real_distribution<double> ray_place(-100.0, 100.0);
  for (int r = 0; r < 500; ++r) {  // a wheel's ray box: 0.7 m down from a mount
    const Eigen::Vector3d lo(ray_place(random), ray_place(random), 0.0);
    const Eigen::Vector3d hi = lo + Eigen::Vector3d(0.01, 0.01, 0.7);
    grid.candidates(lo, hi, candidates);
    CHECK(std::is_sorted(candidates.begin(), candidates.end()));
    CHECK(std::adjacent_find(candidates.begin(), candidates.end()) == candidates.end());
    const std::array<dReal, 6> ray{lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z()};
    for (int i = 0; i < count; ++i)
      if (overlap(grid.box(i), ray)) CHECK(std::binary_search(candidates.begin(), candidates.end(), i));
  }
  dSpaceDestroy(space);
}

TEST_CASE("Box grid: the boxes near one hold every box overlapping it, in ascending order") {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> place(-200.0, 200.0), size(0.5, 6.0);
  std::vector<vehicle::Box> boxes;
  for (int k = 0; k < 400; ++k) {  // cars in a town, and a few long trains of them
    const Eigen::Vector3d lo(place(random), place(random), 0.0);
    const double length = k % 40 == 0 ? 60.0 : size(random);
    boxes.push_back({lo, lo + Eigen::Vector3d(length, size(random), 1.5)});
  }
  vehicle::BoxGrid grid;
  grid.build(boxes, 8.0);
  std::vector<uint32_t> near;
  std::size_t overlapping = 0, found = 0;
  for (int q = 0; q < 400; ++q) {
    const vehicle::Box query = boxes[static_cast<std::size_t>(q)].grown(0.5 + 0.01 * q);
    grid.near(query, near);
    CHECK(std::is_sorted(near.begin(), near.end()));
    CHECK(std::adjacent_find(near.begin(), near.end()) == near.end());
    found += near.size();
    for (uint32_t i = 0; i < boxes.size(); ++i)
      if (query.overlaps(boxes[i])) {
        ++overlapping;
        CHECK(std::binary_search(near.begin(), near.end(), i));
      }
  }
  CHECK(overlapping >= 400);      // each query holds its own box at least
  CHECK(found < 400 * 400 / 10);  // and the grid kept the rest out
}
