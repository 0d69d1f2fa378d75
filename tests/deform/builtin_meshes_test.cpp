// Built-in meshes: closed, outward, the right size and volume, the requested resolution, deterministic,
// mirror-symmetric, wheels in their arches, and bad specs refused naming the key.
#include <deform/builtin_meshes.hpp>
#include <deform/error.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

using namespace deform;

namespace {

/// Every directed edge used once and its reverse used once: closed, two triangles per edge, consistent
/// winding. Returns the number of edges that break that (0 for a good mesh).
std::size_t badEdges(const Mesh& mesh) {
  std::unordered_map<uint64_t, int> uses;
  auto key = [](uint32_t a, uint32_t b) { return (static_cast<uint64_t>(a) << 32) | b; };
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e)
      ++uses[key(t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>((e + 1) % 3)])];
  std::size_t bad = 0;
  for (const auto& [k, n] : uses) {
    const auto a = static_cast<uint32_t>(k >> 32), b = static_cast<uint32_t>(k & 0xffffffffu);
    const auto reverse = uses.find(key(b, a));
    if (n != 1 || reverse == uses.end() || reverse->second != 1) ++bad;
  }
  return bad;
}

double volume_m3(const Mesh& mesh) {
  double six_volume = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions_m[t[0]].cast<double>(),
                          b = mesh.positions_m[t[1]].cast<double>(),
                          c = mesh.positions_m[t[2]].cast<double>();
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6;
}

double smallestTriangleArea_m2(const Mesh& mesh) {
  double smallest = INFINITY;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions_m[t[0]].cast<double>(),
                          b = mesh.positions_m[t[1]].cast<double>(),
                          c = mesh.positions_m[t[2]].cast<double>();
    smallest = std::min(smallest, 0.5 * (b - a).cross(c - a).norm());
  }
  return smallest;
}

void requireClosedOutward(const Mesh& mesh) {
  REQUIRE(badEdges(mesh) == 0);
  REQUIRE(volume_m3(mesh) > 0);
  REQUIRE(smallestTriangleArea_m2(mesh) > 0);
  REQUIRE(mesh.normals.size() == mesh.positions_m.size());
  // A closed surface: the area-weighted normals sum to zero.
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions_m[t[0]].cast<double>(),
                          b = mesh.positions_m[t[1]].cast<double>(),
                          c = mesh.positions_m[t[2]].cast<double>();
    normal_sum += (b - a).cross(c - a);
  }
  CHECK(normal_sum.norm() < 1e-3 * std::sqrt(boundingBox(mesh).diagonal_m()));
}

bool sameMesh(const Mesh& a, const Mesh& b) {
  return a.positions_m == b.positions_m && a.triangles == b.triangles && a.normals == b.normals;
}

double relativeMiss(std::size_t got, std::size_t wanted) {
  return std::abs(static_cast<double>(got) - static_cast<double>(wanted)) / static_cast<double>(wanted);
}

std::string errorOf(const std::string& spec) {
  try {
    makeBuiltin(spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("sedan is a closed outward surface of car size and volume", "[builtin]") {
  const VehicleModel car = makeSedan(20000);
  requireClosedOutward(car.body);
  const Aabb box = boundingBox(car.body);
  CHECK(box.size_m().x() == Approx(4.8).margin(0.05));
  CHECK(box.size_m().y() == Approx(1.8).margin(0.05));
  CHECK(box.max_m.z() == Approx(1.45).margin(0.03));
  CHECK(box.min_m.z() >= 0.14);  // ground clearance under the floor
  CHECK(box.min_m.z() <= 0.20);
  const double volume = volume_m3(car.body);
  CHECK(volume > 6.0);
  CHECK(volume < 10.0);
}

TEST_CASE("sedan vertex count follows the request", "[builtin]") {
  for (std::size_t wanted : {1000u, 20000u, 200000u}) {
    const VehicleModel car = makeSedan(wanted);
    INFO("requested " << wanted << ", got " << car.body.positions_m.size());
    CHECK(relativeMiss(car.body.positions_m.size(), wanted) < 0.05);
    CHECK(badEdges(car.body) == 0);
  }
}

TEST_CASE("sedan reads as a car in profile", "[builtin]") {
  const Mesh body = makeSedan(60000).body;
  // Highest point of the body within a slice of x around `x`, and half-width at the beltline height.
  auto topAt = [&](double x) {
    double top = -1;
    for (const auto& p : body.positions_m)
      if (std::abs(p.x() - x) < 0.03) top = std::max(top, static_cast<double>(p.z()));
    return top;
  };
  auto halfWidthAt = [&](double x, double z_low, double z_high) {
    double w = 0;
    for (const auto& p : body.positions_m)
      if (std::abs(p.x() - x) < 0.03 && p.z() >= z_low && p.z() <= z_high)
        w = std::max(w, static_cast<double>(std::abs(p.y())));
    return w;
  };
  CHECK(topAt(1.6) == Approx(0.85).margin(0.07));   // bonnet
  CHECK(topAt(-0.4) == Approx(1.45).margin(0.03));  // roof
  CHECK(topAt(-2.0) == Approx(1.02).margin(0.06));  // boot
  // Windscreen and rear window: the top rises steadily from bonnet to roof and falls to the boot.
  CHECK(topAt(1.0) < topAt(0.6));
  CHECK(topAt(0.6) < topAt(0.2));
  CHECK(topAt(-1.4) < topAt(-1.0));
  CHECK(topAt(-1.8) < topAt(-1.4));
  // Tumblehome: the greenhouse is narrower than the lower body.
  const double body_half = halfWidthAt(-0.4, 0.4, 0.8), roof_half = halfWidthAt(-0.4, 1.3, 1.5);
  CHECK(body_half == Approx(0.9).margin(0.02));
  CHECK(roof_half < body_half - 0.15);
  // Rounded ends: the nose and tail are narrower than the middle near their tips.
  CHECK(halfWidthAt(2.38, 0, 2) < 0.6);
  CHECK(halfWidthAt(-2.38, 0, 2) < 0.6);
}

TEST_CASE("sedan is mirror-symmetric in Y and deterministic", "[builtin]") {
  const VehicleModel a = makeSedan(5000), b = makeSedan(5000);
  REQUIRE(sameMesh(a.body, b.body));
  std::vector<std::tuple<float, float, float>> points, mirrored;
  for (const auto& p : a.body.positions_m) {
    points.emplace_back(p.x(), p.y(), p.z());
    mirrored.emplace_back(p.x(), -p.y(), p.z());
  }
  std::sort(points.begin(), points.end());
  std::sort(mirrored.begin(), mirrored.end());
  CHECK(points == mirrored);  // exact: the -Y half is the negation of the +Y half
}

TEST_CASE("sedan wheels sit in the arches without touching the body", "[builtin]") {
  const VehicleModel car = makeSedan(200000);
  REQUIRE(car.wheels.size() == 4);
  int steered = 0;
  for (const WheelPart& wheel : car.wheels) {
    INFO("wheel at " << wheel.centre_m.transpose());
    steered += wheel.steered ? 1 : 0;
    CHECK(wheel.steered == (wheel.centre_m.x() > 0));
    CHECK(wheel.radius_m == Approx(0.32).margin(0.02));
    CHECK(wheel.width_m == Approx(0.22).margin(0.02));
    CHECK(wheel.centre_m.z() - wheel.radius_m == Approx(0.0).margin(0.01));  // tyre on the ground
    const Eigen::Vector3f c = wheel.centre_m.cast<float>();
    double surface_above = INFINITY;  // lowest body point straight above the hub, across the tyre width
    std::size_t inside_tyre = 0;
    for (const auto& p : car.body.positions_m) {
      const double dx = p.x() - c.x(), dy = p.y() - c.y(), dz = p.z() - c.z();
      if (std::abs(dy) > wheel.width_m / 2) continue;
      if (std::abs(dx) < 0.02 && dz > 0) surface_above = std::min(surface_above, static_cast<double>(p.z()));
      if (std::hypot(dx, dz) < wheel.radius_m) ++inside_tyre;
    }
    CHECK(surface_above > wheel.centre_m.z());                          // the hub is under the arch top
    CHECK(surface_above > wheel.centre_m.z() + wheel.radius_m);         // and so is the tyre top
    CHECK(surface_above < wheel.centre_m.z() + wheel.radius_m + 0.15);  // a recess, not open sky
    CHECK(inside_tyre == 0);
    // The tyre's outer face is at the body side, not sticking out of it.
    CHECK(std::abs(c.y()) + wheel.width_m / 2 <= 0.9 + 1e-6);
  }
  CHECK(steered == 2);
}

TEST_CASE("sedan surface stays out of the tyres at coarse and fine resolution", "[builtin]") {
  for (std::size_t wanted : {1000u, 20000u}) {
    const VehicleModel car = makeSedan(wanted);
    std::size_t inside = 0;  // points sampled over every triangle that lie inside a tyre
    for (const WheelPart& wheel : car.wheels) {
      for (const auto& t : car.body.triangles) {
        const Eigen::Vector3d a = car.body.positions_m[t[0]].cast<double>(),
                              b = car.body.positions_m[t[1]].cast<double>(),
                              c = car.body.positions_m[t[2]].cast<double>();
        if ((a - wheel.centre_m).norm() > 1.0) continue;  // triangles are far smaller than 0.7 m
        constexpr int kSteps = 8;
        for (int i = 0; i <= kSteps; ++i) {
          for (int j = 0; i + j <= kSteps; ++j) {
            const Eigen::Vector3d d =
                a + (b - a) * (i / double{kSteps}) + (c - a) * (j / double{kSteps}) - wheel.centre_m;
            if (std::abs(d.y()) < wheel.width_m / 2 && std::hypot(d.x(), d.z()) < wheel.radius_m) ++inside;
          }
        }
      }
    }
    INFO(wanted << " vertices");
    CHECK(inside == 0);
  }
}

TEST_CASE("coarsest built-ins are still closed and outward", "[builtin]") {
  const VehicleModel car = makeSedan(100);
  requireClosedOutward(car.body);
  CHECK(relativeMiss(car.body.positions_m.size(), 100) < 0.1);
  CHECK(volume_m3(car.body) > 4.0);  // coarse, but still a car-sized solid
  requireClosedOutward(makeCan(100));
  requireClosedOutward(makeBox(Eigen::Vector3d(1, 2, 3), 100));
  requireClosedOutward(makeBox(Eigen::Vector3d(100, 0.01, 1), 1000));  // extreme aspect
}

TEST_CASE("can has the size and volume of a 330 ml can", "[builtin]") {
  const Mesh can = makeCan(4000);
  requireClosedOutward(can);
  CHECK(relativeMiss(can.positions_m.size(), 4000) < 0.05);
  const Aabb box = boundingBox(can);
  CHECK(box.size_m().x() == Approx(0.066).margin(0.001));
  CHECK(box.size_m().y() == Approx(0.066).margin(0.001));
  CHECK(box.size_m().z() == Approx(0.122).margin(1e-6));  // foot and rim kept as vertices
  const double volume_ml = volume_m3(can) * 1e6;
  CHECK(volume_ml > 330);
  CHECK(volume_ml < 420);
  CHECK(sameMesh(can, makeCan(4000)));
}

TEST_CASE("box is closed, centred, the requested size and subdivided", "[builtin]") {
  const Eigen::Vector3d size(2.0, 0.5, 1.0);
  const Mesh box = makeBox(size, 2000);
  requireClosedOutward(box);
  CHECK(relativeMiss(box.positions_m.size(), 2000) < 0.1);
  const Aabb bounds = boundingBox(box);
  CHECK((bounds.size_m() - size).norm() < 1e-6);
  CHECK((bounds.min_m + bounds.max_m).norm() < 1e-6);
  CHECK(volume_m3(box) == Approx(size.prod()).epsilon(1e-5));
  CHECK(makeBox(Eigen::Vector3d(1, 1, 1), 8).positions_m.size() == 8);
}

TEST_CASE("wheel mesh is a closed cylinder around Y", "[builtin]") {
  const Mesh wheel = makeWheelMesh(0.32, 0.22, 32);
  requireClosedOutward(wheel);
  const Aabb bounds = boundingBox(wheel);
  CHECK(bounds.size_m().y() == Approx(0.22).margin(1e-6));
  CHECK(bounds.size_m().x() == Approx(0.64).margin(1e-3));
  CHECK(bounds.size_m().z() == Approx(0.64).margin(0.01));
  CHECK(volume_m3(wheel) < M_PI * 0.32 * 0.32 * 0.22);
  CHECK(volume_m3(wheel) > 0.9 * M_PI * 0.32 * 0.32 * 0.22);
}

TEST_CASE("builtin specs build the named shape with its parameters", "[builtin]") {
  CHECK(isBuiltinSpec("builtin:sedan"));
  CHECK_FALSE(isBuiltinSpec("car.glb"));
  const VehicleModel car = makeBuiltin("builtin:sedan?vertices=3000");
  CHECK(car.wheels.size() == 4);
  CHECK(relativeMiss(car.body.positions_m.size(), 3000) < 0.05);
  CHECK(car.source == "builtin:sedan?vertices=3000");
  const VehicleModel can = makeBuiltin("builtin:can?vertices=500");
  CHECK(can.wheels.empty());
  CHECK(relativeMiss(can.body.positions_m.size(), 500) < 0.05);
  const VehicleModel box = makeBuiltin("builtin:box?x=3&y=0.5&z=1.5&vertices=1000");
  CHECK((boundingBox(box.body).size_m() - Eigen::Vector3d(3, 0.5, 1.5)).norm() < 1e-5);
  CHECK(box.wheels.empty());
  CHECK(sameMesh(makeBuiltin("builtin:sedan").body, makeSedan(20000).body));
}

TEST_CASE("bad builtin specs are refused naming the spec and the key", "[builtin]") {
  using Catch::Matchers::Contains;
  using Catch::Matchers::StartsWith;
  CHECK_THAT(errorOf("builtin:sedan?vertices=abc"),
             StartsWith("builtin:sedan?vertices=abc: 'vertices' must be a positive integer"));
  CHECK_THAT(errorOf("builtin:sedan?vertices=-5"), Contains("'vertices'"));
  CHECK_THAT(errorOf("builtin:sedan?vertices=50"), Contains("'vertices' must be between"));
  CHECK_THAT(errorOf("builtin:sedan?vertices=60000000"), Contains("'vertices' must be between"));
  CHECK_THAT(errorOf("builtin:sedan?vertices="), Contains("'vertices'"));
  CHECK_THAT(errorOf("builtin:sedan?wheels=3"), StartsWith("builtin:sedan?wheels=3: unknown key 'wheels'"));
  CHECK_THAT(errorOf("builtin:truck"), StartsWith("builtin:truck: unknown built-in 'truck'"));
  CHECK_THAT(errorOf("builtin:box?x=0"), StartsWith("builtin:box?x=0: 'x'"));
  CHECK_THAT(errorOf("builtin:box?y=nan"), Contains("'y'"));
  CHECK_THAT(errorOf("builtin:box?z=-1"), Contains("'z'"));
  CHECK_THAT(errorOf("builtin:box?z=1m"), Contains("'z'"));
  CHECK_THAT(errorOf("builtin:can?vertices=1000&vertices=2000"), Contains("'vertices' given twice"));
  CHECK_THAT(errorOf("builtin:can?vertices"), Contains("'vertices' is not key=value"));
}
