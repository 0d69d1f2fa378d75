// XPBD's promise (Macklin, Mueller, Chentanez 2016, sec. 1 and 4): compliance is a material constant, so
// the static deflection under a load does not depend on the time step or the substep count. Checked
// against the linear-elastic solution K u = f of the same springs (k = 1 / compliance).
#include "fixtures.hpp"

#include <catch2/catch.hpp>
#include <deform/deformable_body.hpp>

#include <Eigen/Dense>

using namespace deform;
using namespace dynamics_test;

namespace {

/// Mean vertical displacement [m] of the linearised spring network under gravity g (minimum-norm
/// solution: the shell's rotation about the core is a free mode that the load does not excite).
double linearSag(const BodySettings& s, double g) {
  const std::size_t n = s.pointCount();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * n);
  auto pair = [&](uint32_t a, uint32_t b, double compliance) {
    const Eigen::Vector3d d = (s.rest_positions_m[a] - s.rest_positions_m[b]).normalized();
    const Eigen::Matrix3d block = d * d.transpose() / compliance;
    k.block<3, 3>(3 * a, 3 * a) += block;
    k.block<3, 3>(3 * b, 3 * b) += block;
    k.block<3, 3>(3 * a, 3 * b) -= block;
    k.block<3, 3>(3 * b, 3 * a) -= block;
  };
  for (const auto& e : s.edges) pair(e.a, e.b, e.compliance_m_per_N);
  for (const auto& b : s.bends) pair(b.left, b.right, b.compliance_m_per_N);
  for (const auto& sp : s.spokes) {
    const Eigen::Vector3d d = (s.rest_positions_m[sp.point] - s.core_m).normalized();
    k.block<3, 3>(3 * sp.point, 3 * sp.point) += d * d.transpose() / sp.compliance_m_per_N;
  }
  for (std::size_t i = 0; i < n; ++i) f[static_cast<Eigen::Index>(3 * i + 2)] = -s.mass_kg[i] * g;
  const Eigen::VectorXd u = k.completeOrthogonalDecomposition().solve(f);
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += u[static_cast<Eigen::Index>(3 * i + 2)];
  return sum / static_cast<double>(n);
}

double simulatedSag(const std::shared_ptr<const BodySettings>& settings, uint32_t substeps,
                    uint32_t iterations, double dt_s, double g) {
  SolverParams params;
  params.substeps = substeps;
  params.iterations = iterations;
  params.damping_per_s = 30.0;
  params.sleep_delay_s = -1;
  DeformableBody body(settings, params);
  StepInputs inputs;
  inputs.chassis.gravity_mps2 = {0, 0, -g};
  const int steps = static_cast<int>(std::ceil(1.5 / dt_s));
  for (int k = 0; k < steps; ++k) body.step(inputs, dt_s);
  double sum = 0;
  for (std::size_t i = 0; i < settings->pointCount(); ++i)
    sum += body.state().positions_m[i].z() - settings->rest_positions_m[i].z();
  return sum / static_cast<double>(settings->pointCount());
}

}  // namespace

TEST_CASE("XPBD: the same compliance gives the same static deflection for any substeps and time step",
          "[dynamics]") {
  BodyDescription d;
  const auto settings = makeSettings(icosahedron(1.0), 1000.0, d, UniformMaterial{2e-6, 1e-5, 1e-5, 1e9});
  const double g = 9.81;
  const double reference = linearSag(*settings, g);
  for (uint32_t iterations : {1u, 4u}) {
    double lowest = 1e9, highest = -1e9;
    for (uint32_t substeps : {1u, 4u, 16u})
      for (double dt : {1.0 / 60, 1.0 / 240, 1.0 / 2000}) {
        const double sag = simulatedSag(settings, substeps, iterations, dt, g);
        const double h = dt / substeps;
        INFO("iterations " << iterations << ", substeps " << substeps << ", dt " << dt << ": sag " << sag
                           << " m, linear " << reference << " m");
        // One Gauss-Seidel sweep of a 16.7 ms substep is the one case that is not converged: there the
        // edges are stiffer than the substep (alpha / h^2 < 1 / m) and 1 sweep leaves 25 %.
        if (iterations == 1 && h > 1.0 / 100) {
          WARN("1 iteration, 1 substep of 1/60 s: sag " << sag / reference * 100
                                                        << " % of the linear answer");
          continue;
        }
        CHECK(sag == Approx(reference).epsilon(0.015));  // within 1.5 % of the linear-elastic answer
        lowest = std::min(lowest, sag);
        highest = std::max(highest, sag);
      }
    const double spread = (highest - lowest) / std::abs(reference);
    WARN("static sag " << reference * 1e3 << " mm (linear); iterations " << iterations << ": spread "
                       << spread * 100 << " % over substeps 1/4/16 x dt 1/60, 1/240, 1/2000 s");
    CHECK(spread < 0.015);
  }
}
