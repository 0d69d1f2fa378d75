// The default car: a loft of cross-sections along X between two poles (rounded nose and tail), the
// Y < 0 half an exact mirror of the Y > 0 half. Vehicle frame with the origin on the ground under the
// middle of the car (the control mesh recentres on the centre of mass later).
#include <deform/builtin_meshes.hpp>

#include "builtin_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace deform {
namespace {

using builtin::ProfileCurve;
using builtin::SmoothProfile;

constexpr double kHalfLength_m = 2.4;
constexpr double kNoseLength_m = 0.30;  // length of the rounded end zones
constexpr double kEndExponent = 3.0;    // superellipse exponent of the ends: higher = blunter
constexpr double kWheelRadius_m = 0.32;
constexpr double kWheelWidth_m = 0.22;
constexpr double kFrontAxle_m = 1.45;  // wheelbase 2.8 m
constexpr double kRearAxle_m = -1.35;
constexpr double kWheelCentreY_m = 0.77;  // tyre outer face 0.02 m inside the body side
constexpr double kArchRadius_m = 0.39;    // 0.07 m clearance around the tyre
constexpr double kArchRamp_m = 0.04;      // the recess fades in over this length beyond the arch
constexpr double kArchInnerY_m = 0.62;    // wheel-well wall, inboard of the tyre's inner face (0.66)
constexpr double kBottomRadius_m = 0.05;
constexpr double kShoulderRadius_m = 0.07;
constexpr double kTumblehome = 0.35;  // inward lean of the side glass, dy/dz
constexpr double kLedge_m = 0.06;     // shoulder ledge between body side and glass

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

/// The car's shape as functions of x: side profile, plan view and the section built from them.
class SedanShape {
 public:
  /// Centreline top: nose, bonnet, windscreen, roof, rear window, boot deck, tail.
  SmoothProfile top_m{{{-2.4, 0.98},
                       {-2.0, 1.02},
                       {-1.6, 1.03},
                       {-1.3, 1.20},
                       {-0.95, 1.41},
                       {-0.4, 1.45},
                       {0.05, 1.43},
                       {0.45, 1.22},
                       {0.85, 0.92},
                       {1.2, 0.88},
                       {1.8, 0.82},
                       {2.2, 0.76},
                       {2.4, 0.70}}};
  /// Beltline: top edge of the lower body (bonnet and boot edges, window sills).
  SmoothProfile belt_m{{{-2.4, 0.96},
                        {-1.6, 1.00},
                        {-0.9, 0.98},
                        {0.3, 0.94},
                        {0.85, 0.90},
                        {1.2, 0.86},
                        {1.8, 0.80},
                        {2.4, 0.68}}};
  /// Underside; rises at the ends for approach and departure angles.
  SmoothProfile floor_m{{{-2.4, 0.34}, {-2.0, 0.22}, {-1.5, 0.17}, {1.5, 0.17}, {2.0, 0.22}, {2.4, 0.32}}};
  /// Half-width of the lower body.
  SmoothProfile half_width_m{
      {{-2.4, 0.80}, {-2.1, 0.87}, {-1.6, 0.90}, {1.6, 0.90}, {2.1, 0.86}, {2.4, 0.78}}};

  /// End-zone scale: 1 in the middle, falling to 0 at the nose and tail along a superellipse.
  static double endScale(double x) {
    const double into = std::max(0.0, std::abs(x) - (kHalfLength_m - kNoseLength_m)) / kNoseLength_m;
    if (into >= 1) return 0;
    return std::pow(1 - std::pow(into, kEndExponent), 1 / kEndExponent);
  }
  /// Height the end zones shrink towards (becomes the nose and tail tip).
  double centreZ_m(double x) const { return 0.5 * (floor_m(x) + top_m(x)); }

  /// How far the wheel-well recess is cut in (1 within the arch), and the arch top z at x.
  static void arch(double x, double& depth_fraction, double& arch_z_m) {
    depth_fraction = 0;
    arch_z_m = kWheelRadius_m;
    for (double axle : {kFrontAxle_m, kRearAxle_m}) {
      const double dx = std::abs(x - axle);
      const double f = 1 - smoothstep(kArchRadius_m, kArchRadius_m + kArchRamp_m, dx);
      if (f <= depth_fraction) continue;
      depth_fraction = f;
      arch_z_m = kWheelRadius_m + std::sqrt(std::max(0.0, kArchRadius_m * kArchRadius_m - dx * dx));
    }
  }

  /// Half cross-section at x (Y >= 0, unscaled), from the bottom centreline round the side to the top
  /// centreline, in three parts whose joints are always vertices so the visible edges stay straight
  /// lines from station to station: (0) floor, bottom corner and wheel well (when in an arch) out to
  /// the arch edge; (1) side and shoulder up to the window sill; (2) side glass leaning in
  /// (tumblehome), roof corner and roof. Over bonnet and boot the glass height is ~0, so part 2 reads
  /// as a crowned panel.
  void halfSection(double x, std::array<ProfileCurve, 3>& parts) const {
    const double floor = floor_m(x), belt = belt_m(x), w = half_width_m(x);
    const double top = std::max(top_m(x), belt + 0.005);
    double depth_fraction = 0, arch_z = 0;
    arch(x, depth_fraction, arch_z);
    const double inner_w = w - depth_fraction * (w - kArchInnerY_m);
    const double well_top = std::clamp(arch_z, floor + kBottomRadius_m, belt - kShoulderRadius_m);
    const double glass_h = top - belt;
    const double ledge = kLedge_m * smoothstep(0.05, 0.25, glass_h);
    const double roof_r = std::min(0.12, 0.45 * glass_h);
    const double glass_base = w - kShoulderRadius_m - ledge;
    const double glass_top = glass_base - kTumblehome * (glass_h - roof_r);
    constexpr double kQuarter = std::numbers::pi / 2;

    for (auto& part : parts) part.clear();
    parts[0].moveTo({0, floor});
    parts[0].lineTo({inner_w - kBottomRadius_m, floor});
    parts[0].arc({inner_w - kBottomRadius_m, floor + kBottomRadius_m}, kBottomRadius_m, -kQuarter, 0);
    parts[0].lineTo({inner_w, well_top});
    parts[0].lineTo({w, well_top});
    parts[1].moveTo({w, well_top});
    parts[1].lineTo({w, belt - kShoulderRadius_m});
    parts[1].arc({w - kShoulderRadius_m, belt - kShoulderRadius_m}, kShoulderRadius_m, 0, kQuarter);
    parts[1].lineTo({glass_base, belt});
    parts[2].moveTo({glass_base, belt});
    parts[2].lineTo({glass_top, top - roof_r});
    parts[2].arc({glass_top - roof_r, top - roof_r}, roof_r, 0, kQuarter);
    parts[2].lineTo({0, top});
  }

  /// Points whose motion along x sets how densely stations are placed (see stationPositions).
  std::array<Eigen::Vector2d, 4> markers(double x) const {
    const double s = endScale(x), zc = centreZ_m(x);
    double depth_fraction = 0, arch_z = 0;
    arch(x, depth_fraction, arch_z);
    const double w = half_width_m(x);
    auto scaled = [&](double y, double z) { return Eigen::Vector2d(s * y, zc + s * (z - zc)); };
    return {scaled(w, belt_m(x)), scaled(0.6 * w, top_m(x)),
            scaled(w - depth_fraction * (w - kArchInnerY_m), arch_z), scaled(0.5 * w, floor_m(x))};
  }
};

/// Station x positions, denser where the surface turns quickly (windscreen, arch edges, nose, tail):
/// evenly spaced in a length that adds how fast the section's markers move per metre of x.
std::vector<double> stationPositions(const SedanShape& shape, std::size_t stations, double& metric_length_m) {
  constexpr std::size_t kSamples = 1 << 16;
  std::vector<double> cumulative(kSamples + 1, 0.0);
  const double dx = 2 * kHalfLength_m / kSamples;
  auto previous = shape.markers(-kHalfLength_m);
  for (std::size_t k = 1; k <= kSamples; ++k) {
    const auto current = shape.markers(-kHalfLength_m + dx * static_cast<double>(k));
    double move2 = 0;
    for (std::size_t m = 0; m < current.size(); ++m)
      move2 = std::max(move2, (current[m] - previous[m]).squaredNorm());
    cumulative[k] = cumulative[k - 1] + std::sqrt(dx * dx + move2);
    previous = current;
  }
  metric_length_m = cumulative.back();
  std::vector<double> xs(stations);
  std::size_t k = 0;
  for (std::size_t i = 0; i < stations; ++i) {
    const double target = metric_length_m * static_cast<double>(i) / static_cast<double>(stations - 1);
    while (k + 1 < kSamples && cumulative[k + 1] < target) ++k;
    const double span = cumulative[k + 1] - cumulative[k];
    const double f = span > 0 ? std::clamp((target - cumulative[k]) / span, 0.0, 1.0) : 0.0;
    xs[i] = -kHalfLength_m + dx * (static_cast<double>(k) + f);
  }
  xs.front() = -kHalfLength_m;
  xs.back() = kHalfLength_m;
  return xs;
}

/// Ring size (even, for the mirror) and ring count whose product is closest to the vertex target, with
/// cells about as long as they are wide.
void chooseGrid(std::size_t target_vertices, double ring_length_m, double metric_length_m,
                std::size_t& ring_size, std::size_t& rings) {
  const double n = static_cast<double>(std::max<std::size_t>(target_vertices, 16));
  const double ideal = std::sqrt(n * ring_length_m / metric_length_m);
  const auto centre = static_cast<long long>(std::llround(ideal / 2)) * 2;
  long long best_error = -1;
  for (long long candidate = std::max(8LL, centre - 6); candidate <= std::max(8LL, centre + 6);
       candidate += 2) {
    const auto r = std::max(1LL, std::llround((n - 2) / static_cast<double>(candidate)));
    const long long error = std::llabs(r * candidate + 2 - static_cast<long long>(n)) * 4 +
                            std::llabs(candidate - centre);  // prefer the count, then the shape
    if (best_error < 0 || error < best_error) {
      best_error = error;
      ring_size = static_cast<std::size_t>(candidate);
      rings = static_cast<std::size_t>(r);
    }
  }
}

}  // namespace

VehicleModel makeSedan(std::size_t target_vertices) {
  const SedanShape shape;
  std::array<ProfileCurve, 3> parts;
  shape.halfSection(-0.3, parts);  // widest and tallest section sets the ring spacing
  const double part_lengths_m[3] = {parts[0].length_m(), parts[1].length_m(), parts[2].length_m()};
  const double half_length_m = part_lengths_m[0] + part_lengths_m[1] + part_lengths_m[2];
  double metric_length_m = 0;
  stationPositions(shape, 3, metric_length_m);
  std::size_t ring_size = 8, rings = 1;
  chooseGrid(target_vertices, 2 * half_length_m, metric_length_m, ring_size, rings);
  const std::vector<double> xs = stationPositions(shape, rings + 2, metric_length_m);

  VehicleModel model;
  model.source = "builtin:sedan";
  Mesh& mesh = model.body;
  builtin::poleGridTopology(rings, ring_size, mesh);
  mesh.positions_m.front() = Eigen::Vector3d(xs.front(), 0, shape.centreZ_m(xs.front())).cast<float>();
  mesh.positions_m.back() = Eigen::Vector3d(xs.back(), 0, shape.centreZ_m(xs.back())).cast<float>();

  // Edges per part in proportion to the reference section, at least one each.
  const std::size_t half = ring_size / 2;
  std::array<std::size_t, 3> part_edges{};
  part_edges[0] = std::clamp<std::size_t>(
      static_cast<std::size_t>(std::llround(static_cast<double>(half) * part_lengths_m[0] / half_length_m)),
      1, half - 2);
  part_edges[1] = std::clamp<std::size_t>(
      static_cast<std::size_t>(std::llround(static_cast<double>(half) * part_lengths_m[1] / half_length_m)),
      1, half - 1 - part_edges[0]);
  part_edges[2] = half - part_edges[0] - part_edges[1];
  std::vector<Eigen::Vector2d> points(half + 1);
  for (std::size_t r = 0; r < rings; ++r) {
    const double x = xs[r + 1], s = SedanShape::endScale(x), zc = shape.centreZ_m(x);
    shape.halfSection(x, parts);
    std::size_t first = 0;  // each part's first point is the previous part's last
    for (std::size_t k = 0; k < parts.size(); ++k) {
      parts[k].sample(part_edges[k] + 1, points.data() + first);
      first += part_edges[k];
    }
    // j runs from the bottom centreline up the +Y side to the top (outward = d_j x d_ring, d_ring = +X);
    // the -Y side is the exact negation, so the car is mirror-symmetric to the bit.
    for (std::size_t j = 0; j <= half; ++j) {
      const auto y = static_cast<float>(s * points[j].x());
      const auto z = static_cast<float>(zc + s * (points[j].y() - zc));
      const auto xf = static_cast<float>(x);
      mesh.positions_m[builtin::ringVertex(r, j, ring_size)] = {xf, j == 0 || j == half ? 0.0f : y, z};
      if (j > 0 && j < half) mesh.positions_m[builtin::ringVertex(r, ring_size - j, ring_size)] = {xf, -y, z};
    }
  }
  computeVertexNormals(mesh);

  for (double axle : {kFrontAxle_m, kRearAxle_m}) {
    for (double side : {1.0, -1.0}) {
      WheelPart wheel;
      wheel.centre_m = {axle, side * kWheelCentreY_m, kWheelRadius_m};
      wheel.radius_m = kWheelRadius_m;
      wheel.width_m = kWheelWidth_m;
      wheel.steered = axle > 0;
      model.wheels.push_back(wheel);
    }
  }
  return model;
}

}  // namespace deform
