#pragma once
// What the skin tests share: the car they skin, and the partition-of-unity measure of a skin's weights.
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/mesh.hpp>
#include <deform/skin.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace skin_test {

/// The built-in sedan at `vertices` vertices and its control points (`points` of them).
struct Sedan {
  deform::VehicleModel car;
  std::vector<Eigen::Vector3d> control;
  Eigen::Vector3d centre_m;  ///< the middle of the body's bounding box [m]
  explicit Sedan(std::size_t vertices = 20000, std::size_t points = 60) : car(deform::makeSedan(vertices)) {
    std::vector<Eigen::Vector3d> body;
    for (const auto& p : car.body.positions_m) body.push_back(p.cast<double>());
    control = deform::buildControlMesh(body, points).points_m;
    const deform::Aabb box = deform::boundingBox(car.body);
    centre_m = 0.5 * (box.min_m + box.max_m);
  }
  const std::vector<Eigen::Vector3f>& rest() const { return car.body.positions_m; }
  /// A dent-sized field: up to 12 cm, pointing inwards, varying from point to point.
  std::vector<Eigen::Vector3d> dent() const {
    std::vector<Eigen::Vector3d> d(control.size());
    for (std::size_t i = 0; i < d.size(); ++i)
      d[i] = -0.1 * control[i].normalized() * (1.0 + 0.2 * std::sin(3.0 * static_cast<double>(i)));
    return d;
  }
};

/// The largest |sum of a vertex's weights - 1| over the skin's vertices (0: a partition of unity).
inline double largestWeightSumError(const deform::Skin& skin) {
  double worst = 0;
  for (std::size_t j = 0; j < skin.vertexCount(); ++j) {
    double sum = 0;
    for (std::size_t k = 0; k < skin.influences(); ++k) sum += skin.slotWeight(j, k);
    worst = std::max(worst, std::abs(sum - 1.0));
  }
  return worst;
}

}  // namespace skin_test
