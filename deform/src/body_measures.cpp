// Measures of a body's state: its energy, its largest deviation, its constraint residual.
#include <deform/deformable_body.hpp>

#include <algorithm>
#include <cmath>

namespace deform {

BodyEnergy bodyEnergy(const BodySettings& settings, const BodyState& state) {
  BodyEnergy e;
  const auto& x = state.positions_m;
  for (std::size_t i = 0; i < x.size(); ++i)
    e.kinetic_J += 0.5 * settings.mass_kg[i] * state.velocities_mps[i].squaredNorm();
  auto elastic = [&e](double c, double compliance) {
    if (compliance > 0) e.elastic_J += 0.5 * c * c / compliance;
  };
  for (std::size_t k = 0; k < settings.edges.size(); ++k) {
    const auto& c = settings.edges[k];
    elastic((x[c.a] - x[c.b]).norm() - state.edge_rest_m[k], c.compliance_m_per_N);
  }
  for (std::size_t k = 0; k < settings.spokes.size(); ++k) {
    const auto& c = settings.spokes[k];
    if (settings.anchored_columns) {
      elastic((x[c.point] - state.column_rest_m[k]).norm(), c.compliance_m_per_N);
      continue;
    }
    elastic((x[c.point] - settings.core_m - settings.spoke_anchor_m[k]).norm() - state.spoke_rest_m[k],
            c.compliance_m_per_N);
  }
  for (std::size_t k = 0; k < settings.bends.size(); ++k) {
    const auto& c = settings.bends[k];
    elastic((x[c.left] - x[c.right]).norm() - state.bend_rest_m[k], c.compliance_m_per_N);
  }
  return e;
}

double maxDeviation(const BodySettings& settings, const BodyState& state) {
  double worst2 = 0;
  for (std::size_t i = 0; i < state.positions_m.size(); ++i)
    worst2 = std::max(worst2, (state.positions_m[i] - settings.rest_positions_m[i]).squaredNorm());
  return std::sqrt(worst2);
}

double constraintStrainRms(const BodySettings& settings, const BodyState& state) {
  double sum2 = 0;
  std::size_t count = 0;
  const auto add = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double rest_m) {
    if (!(rest_m > 0)) return;
    const double strain = ((a - b).norm() - rest_m) / rest_m;
    sum2 += strain * strain;
    ++count;
  };
  const auto& x = state.positions_m;
  for (std::size_t k = 0; k < settings.edges.size(); ++k)
    add(x[settings.edges[k].a], x[settings.edges[k].b], state.edge_rest_m[k]);
  for (std::size_t k = 0; k < settings.spokes.size(); ++k) {
    if (settings.anchored_columns) {  // the column's displacement from its rest place over its length
      const double strain =
          (x[settings.spokes[k].point] - state.column_rest_m[k]).norm() / settings.spoke_rest_m[k];
      sum2 += strain * strain;
      ++count;
      continue;
    }
    add(x[settings.spokes[k].point], settings.core_m + settings.spoke_anchor_m[k], state.spoke_rest_m[k]);
  }
  for (std::size_t k = 0; k < settings.bends.size(); ++k)
    add(x[settings.bends[k].left], x[settings.bends[k].right], state.bend_rest_m[k]);
  return count > 0 ? std::sqrt(sum2 / static_cast<double>(count)) : 0.0;
}

}  // namespace deform
