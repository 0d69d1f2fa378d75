#include "fixtures.hpp"

#include "../point_sets.hpp"

#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/masses.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dynamics_test {

deform::ControlMesh icosahedron(double radius_m) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> points;
  for (double s1 : {-1.0, 1.0})
    for (double s2 : {-1.0, 1.0}) {
      points.emplace_back(0, s1, s2 * phi);
      points.emplace_back(s1, s2 * phi, 0);
      points.emplace_back(s2 * phi, 0, s1);
    }
  for (auto& p : points) p = p.normalized() * radius_m;
  return deform::convexHull(points, "icosahedron");
}

deform::ControlMesh sphereHull(std::size_t count, double radius_m) {
  if (count == 4) {
    std::vector<Eigen::Vector3d> tetra{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    for (auto& p : tetra) p = p.normalized() * radius_m;
    return deform::convexHull(tetra, "tetrahedron");
  }
  return deform::convexHull(test_points::sphere(count, {radius_m, radius_m, radius_m}), "sphere");
}

std::shared_ptr<const deform::BodySettings> makeSettings(const deform::ControlMesh& mesh, double mass_kg,
                                                         const deform::BodyDescription& description) {
  const deform::MassSplit masses = deform::distributeMass(mesh, mass_kg);
  return std::make_shared<const deform::BodySettings>(deform::createBodySettings(mesh, masses, description));
}

std::shared_ptr<const deform::BodySettings> makeSettings(const deform::ControlMesh& mesh, double mass_kg,
                                                         const deform::BodyDescription& description,
                                                         const UniformMaterial& uniform) {
  deform::BodySettings s = *makeSettings(mesh, mass_kg, description);
  auto set = [&](auto& constraints, const std::vector<double>& rest, std::vector<deform::YieldLimits>& yield,
                 double compliance) {
    for (std::size_t k = 0; k < constraints.size(); ++k) {
      constraints[k].compliance_m_per_N = compliance;
      yield[k] = {uniform.yield_strain * rest[k], uniform.yield_strain * rest[k]};
    }
  };
  set(s.edges, s.edge_rest_m, s.edge_yield, uniform.edge_compliance_m_per_N);
  set(s.spokes, s.spoke_rest_m, s.spoke_yield, uniform.spoke_compliance_m_per_N);
  set(s.bends, s.bend_rest_m, s.bend_yield, uniform.bend_compliance_m_per_N);
  return std::make_shared<const deform::BodySettings>(std::move(s));
}

UniformMaterial elasticMaterial(double compliance_m_per_N) {
  return {compliance_m_per_N, compliance_m_per_N, compliance_m_per_N, 1e9};
}

std::vector<deform::ContactShape> radialPlates(const deform::BodySettings& settings, double reach_m) {
  std::vector<deform::ContactShape> plates;
  for (const Eigen::Vector3d& p : settings.rest_positions_m) {
    const Eigen::Vector3d out = (p - settings.core_m).normalized();
    // Solid where -out . x < -(out . core + reach): beyond `reach` from the core along `out`.
    plates.push_back(deform::HalfSpaceShape{-out, -(out.dot(settings.core_m) + reach_m)});
  }
  return plates;
}

double largestMagnitude(const deform::BodyState& state) {
  double worst = 0;
  auto see = [&worst](double v) {
    worst = std::isfinite(v) ? std::max(worst, std::abs(v)) : std::numeric_limits<double>::infinity();
  };
  for (const auto& p : state.positions_m)
    for (int a = 0; a < 3; ++a) see(p[a]);
  for (const auto& v : state.velocities_mps)
    for (int a = 0; a < 3; ++a) see(v[a]);
  for (double r : state.edge_rest_m) see(r);
  for (double r : state.spoke_rest_m) see(r);
  for (double r : state.bend_rest_m) see(r);
  see(state.plastic_work_J);
  return worst;
}

double worstDeviationExcess(const deform::BodySettings& settings, const deform::BodyState& state) {
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < settings.pointCount(); ++i) {
    const double d = (state.positions_m[i] - settings.rest_positions_m[i]).norm();
    worst = std::isfinite(d) ? std::max(worst, d - settings.max_deviation_m[i])
                             : std::numeric_limits<double>::infinity();
  }
  return worst;
}

double meanRadius(const deform::BodySettings& settings, const deform::BodyState& state) {
  double sum = 0;
  for (const auto& p : state.positions_m) sum += (p - settings.core_m).norm();
  return sum / static_cast<double>(state.positions_m.size());
}

deform::ControlMesh sedanControlMesh(std::size_t points) {
  const deform::VehicleModel car = deform::makeSedan(2000);
  std::vector<Eigen::Vector3d> cloud;
  for (const auto& p : car.body.positions_m) cloud.push_back(p.cast<double>());
  return deform::buildControlMesh(cloud, points, "sedan");
}

}  // namespace dynamics_test
