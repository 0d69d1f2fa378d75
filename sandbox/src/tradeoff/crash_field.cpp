#include "tradeoff/crash_field.hpp"

#include <scenes/scene_file.hpp>
#include <scenes/scene_run.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace sandbox {
namespace {

struct Samples {
  std::vector<Eigen::Vector3d> rest_m, displacement_m;
  double sigma_m = 0;
};

double meanNearestSpacing_m(const std::vector<Eigen::Vector3d>& points) {
  double sum_m = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double nearest2 = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < points.size(); ++j)
      if (j != i) nearest2 = std::min(nearest2, (points[i] - points[j]).squaredNorm());
    sum_m += std::sqrt(nearest2);
  }
  return sum_m / static_cast<double>(points.size());
}

}  // namespace

KnownField wallCrashField(std::size_t control_points) {
  const scenes::SceneConfig scene = scenes::loadScene(
      "wall_crash",
      {scenes::parseOverride("vehicle.deformation.control_points=" + std::to_string(control_points))});
  std::printf("skin error: the wall crash at %zu control points, to its end (%.1f s)\n", control_points,
              scene.duration_s);
  std::fflush(stdout);
  scenes::SceneRun run(scene);
  run.stepUntil(scene.duration_s);
  auto samples = std::make_shared<Samples>();
  const vehicle::CarId car = run.carId(0);
  samples->rest_m = run.simulation().controlRestPoints(car);
  samples->displacement_m = run.simulation().controlDisplacements(car);
  samples->sigma_m = meanNearestSpacing_m(samples->rest_m);
  double deepest_m = 0;
  for (const Eigen::Vector3d& d : samples->displacement_m) deepest_m = std::max(deepest_m, d.norm());
  std::printf("skin error: its dent, %zu points, largest displacement %.3f m, sigma %.3f m\n",
              samples->rest_m.size(), deepest_m, samples->sigma_m);
  char formula[200];
  std::snprintf(formula, sizeof formula,
                "the 56 km/h wall crash's residual dent at %zu control points, Gaussian kernel average, "
                "sigma %.3f m",
                samples->rest_m.size(), samples->sigma_m);
  return {"wall_crash", formula, [samples](const Eigen::Vector3d& p) {
            // Exponents relative to the nearest point's, so that a point far from all of them still has
            // weights (the same field: the common factor cancels).
            const double inv_2s2 = 0.5 / (samples->sigma_m * samples->sigma_m);
            double nearest2 = std::numeric_limits<double>::infinity();
            for (const Eigen::Vector3d& c : samples->rest_m)
              nearest2 = std::min(nearest2, (p - c).squaredNorm());
            Eigen::Vector3d sum{0, 0, 0};
            double weight_sum = 0;
            for (std::size_t i = 0; i < samples->rest_m.size(); ++i) {
              const double g = std::exp(-((p - samples->rest_m[i]).squaredNorm() - nearest2) * inv_2s2);
              sum += g * samples->displacement_m[i];
              weight_sum += g;
            }
            return Eigen::Vector3d(sum / weight_sum);
          }};
}

}  // namespace sandbox
