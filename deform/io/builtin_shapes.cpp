// The simple built-in shapes: a drinks can and a wheel (surfaces of revolution between two poles) and
// a subdivided box.
#include <deform/builtin_meshes.hpp>
#include <deform/error.hpp>

#include "builtin_grid.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <numbers>

namespace deform {
namespace {

/// Revolves a profile (radius, height) whose two ends lie on the axis into a closed mesh of about
/// `target_vertices` vertices. `place(radius, height, angle)` maps to the vehicle frame and must make
/// d_angle x d_profile point outward.
template <class Place>
Mesh revolve(const std::vector<Eigen::Vector2d>& profile, std::size_t target_vertices,
             std::size_t min_segments, Place place) {
  builtin::ProfileCurve curve;
  curve.moveTo(profile.front());
  for (std::size_t i = 1; i < profile.size(); ++i) curve.lineTo(profile[i]);
  double max_radius = 0;
  for (const auto& p : profile) max_radius = std::max(max_radius, p.x());
  // Square-ish cells: segments / circumference ~ rings / profile length.
  const double n = static_cast<double>(target_vertices);
  const double circumference = 2 * std::numbers::pi * max_radius;
  const auto segments = std::max<std::size_t>(
      min_segments, static_cast<std::size_t>(std::llround(std::sqrt(n * circumference / curve.length_m()))));
  const auto rings = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::llround((n - 2) / static_cast<double>(segments))));

  Mesh mesh;
  builtin::poleGridTopology(rings, segments, mesh);
  std::vector<Eigen::Vector2d> points(rings + 2);
  builtin::samplePolyline(profile, rings + 2, points.data());
  mesh.positions_m.front() = place(0.0, points.front().y(), 0.0);
  mesh.positions_m.back() = place(0.0, points.back().y(), 0.0);
  for (std::size_t r = 0; r < rings; ++r) {
    for (std::size_t j = 0; j < segments; ++j) {
      const double angle = 2 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(segments);
      mesh.positions_m[builtin::ringVertex(r, j, segments)] =
          place(points[r + 1].x(), points[r + 1].y(), angle);
    }
  }
  computeVertexNormals(mesh);
  return mesh;
}

}  // namespace

Mesh makeCan(std::size_t target_vertices) {
  // Half profile (radius, height) [m] from the centre of the domed bottom round to the centre of the
  // lid: foot ring, chime, straight wall, necked shoulder, rim, recessed lid.
  const std::vector<Eigen::Vector2d> profile = {{0.0, 0.010},     {0.020, 0.006},   {0.0245, 0.0},
                                                {0.0300, 0.0025}, {0.0330, 0.0120}, {0.0330, 0.1080},
                                                {0.0300, 0.1170}, {0.0295, 0.1205}, {0.0290, 0.1220},
                                                {0.0276, 0.1220}, {0.0270, 0.1185}, {0.0, 0.1185}};
  return revolve(profile, target_vertices, 8, [](double radius, double height, double angle) {
    return Eigen::Vector3f(static_cast<float>(radius * std::cos(angle)),
                           static_cast<float>(radius * std::sin(angle)), static_cast<float>(height));
  });
}

Mesh makeWheelMesh(double radius_m, double width_m, int segments) {
  assert(radius_m > 0 && width_m > 0 && segments >= 3);
  const double corner = std::min(0.025, 0.2 * std::min(radius_m, width_m));
  const double h = width_m / 2;
  // (radius, y) from the hub centre of the -Y face round the tread to the +Y face.
  const std::vector<Eigen::Vector2d> profile = {{0.0, -h},
                                                {0.6 * radius_m, -h},
                                                {radius_m - corner, -h},
                                                {radius_m, -h + corner},
                                                {radius_m, h - corner},
                                                {radius_m - corner, h},
                                                {0.6 * radius_m, h},
                                                {0.0, h}};
  const auto n = static_cast<std::size_t>(segments);
  builtin::ProfileCurve curve;  // the fixed profile points are the rings; no resampling
  Mesh mesh;
  const std::size_t rings = profile.size() - 2;
  builtin::poleGridTopology(rings, n, mesh);
  // Angle runs so that d_angle x d_profile is outward: (r cos a, y, -r sin a).
  auto place = [](double r, double y, double a) {
    return Eigen::Vector3f(static_cast<float>(r * std::cos(a)), static_cast<float>(y),
                           static_cast<float>(-r * std::sin(a)));
  };
  mesh.positions_m.front() = place(0, -h, 0);
  mesh.positions_m.back() = place(0, h, 0);
  for (std::size_t r = 0; r < rings; ++r) {
    for (std::size_t j = 0; j < n; ++j) {
      const double angle = 2 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(n);
      mesh.positions_m[builtin::ringVertex(r, j, n)] = place(profile[r + 1].x(), profile[r + 1].y(), angle);
    }
  }
  computeVertexNormals(mesh);
  return mesh;
}

namespace {

/// Surface vertices of an a x b x c cell lattice (the box grid without its interior).
std::size_t boxVertexCount(const std::array<std::size_t, 3>& cells) {
  // Plain names, not a structured binding: clang 14 (the sanitizer build) cannot capture those in lambdas.
  const std::size_t a = cells[0], b = cells[1], c = cells[2];
  return (a + 1) * (b + 1) * (c + 1) - (a - 1) * (b - 1) * (c - 1);
}

std::array<std::size_t, 3> boxCells(const Eigen::Vector3d& size_m, double cell_m) {
  std::array<std::size_t, 3> cells{};
  for (int k = 0; k < 3; ++k)
    cells[static_cast<std::size_t>(k)] =
        static_cast<std::size_t>(std::clamp(std::llround(size_m[k] / cell_m), 1LL, 1LL << 20));
  return cells;
}

}  // namespace

Mesh makeBox(const Eigen::Vector3d& size_m, std::size_t target_vertices) {
  if (!size_m.allFinite() || size_m.minCoeff() <= 0)
    throw InputError("box: sizes must be positive and finite");
  // Square-ish cells: bisect the cell size (in log space) on the surface vertex count.
  double lo = std::log(size_m.maxCoeff() * 1e-6), hi = std::log(size_m.maxCoeff());
  for (int it = 0; it < 80; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (boxVertexCount(boxCells(size_m, std::exp(mid))) > target_vertices)
      lo = mid;
    else
      hi = mid;
  }
  std::array<std::size_t, 3> cells = boxCells(size_m, std::exp(hi));
  const std::array<std::size_t, 3> finer = boxCells(size_m, std::exp(lo));
  auto miss = [&](const std::array<std::size_t, 3>& c) {
    const auto v = static_cast<long long>(boxVertexCount(c));
    return std::llabs(v - static_cast<long long>(target_vertices));
  };
  if (miss(finer) < miss(cells)) cells = finer;
  // Plain names, not a structured binding: clang 14 (the sanitizer build) cannot capture those in lambdas.
  const std::size_t a = cells[0], b = cells[1], c = cells[2];

  // Vertex order: bottom layer (full grid), rings of the side walls, top layer (full grid).
  const std::size_t ring = 2 * (a + b), bottom = (a + 1) * (b + 1);
  auto ringIndex = [a, b](std::size_t i, std::size_t j) -> std::size_t {
    if (j == 0) return i;
    if (i == a) return a + j;
    if (j == b) return a + b + (a - i);
    return 2 * a + b + (b - j);
  };
  auto index = [&](const std::array<std::size_t, 3>& l) -> uint32_t {
    const auto [i, j, k] = l;
    if (k == 0) return static_cast<uint32_t>(j * (a + 1) + i);
    if (k == c) return static_cast<uint32_t>(bottom + (c - 1) * ring + j * (a + 1) + i);
    return static_cast<uint32_t>(bottom + (k - 1) * ring + ringIndex(i, j));
  };
  Mesh mesh;
  mesh.positions_m.resize(boxVertexCount(cells));
  auto setPosition = [&](std::size_t i, std::size_t j, std::size_t k) {
    const Eigen::Vector3d f(static_cast<double>(i) / static_cast<double>(a),
                            static_cast<double>(j) / static_cast<double>(b),
                            static_cast<double>(k) / static_cast<double>(c));
    mesh.positions_m[index({i, j, k})] = ((f.array() - 0.5) * size_m.array()).matrix().cast<float>();
  };
  for (std::size_t k = 0; k <= c; ++k)
    for (std::size_t j = 0; j <= b; ++j)
      for (std::size_t i = 0; i <= a; ++i)
        if (k == 0 || k == c || i == 0 || i == a || j == 0 || j == b) setPosition(i, j, k);

  // Each face: fixed axis and side, then (u, v) axes with u x v = outward normal.
  struct Face {
    std::size_t axis, u, v;
    bool high;
  };
  const std::array<Face, 6> faces = {{{2, 1, 0, false},
                                      {2, 0, 1, true},
                                      {0, 2, 1, false},
                                      {0, 1, 2, true},
                                      {1, 0, 2, false},
                                      {1, 2, 0, true}}};
  for (const Face& face : faces) {
    const std::size_t nu = cells[face.u], nv = cells[face.v];
    for (std::size_t u = 0; u < nu; ++u) {
      for (std::size_t v = 0; v < nv; ++v) {
        auto at = [&](std::size_t du, std::size_t dv) {
          std::array<std::size_t, 3> l{};
          l[face.axis] = face.high ? cells[face.axis] : 0;
          l[face.u] = u + du;
          l[face.v] = v + dv;
          return index(l);
        };
        mesh.triangles.push_back({at(0, 0), at(1, 0), at(1, 1)});
        mesh.triangles.push_back({at(0, 0), at(1, 1), at(0, 1)});
      }
    }
  }
  computeVertexNormals(mesh);
  return mesh;
}

}  // namespace deform
