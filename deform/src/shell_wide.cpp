// The shell orientation constraint's passes, four points at a time (shell_wide.hpp).
#include "shell_wide.hpp"

#include <deform/constraints.hpp>
#include <deform/solver_params.hpp>

#include "simd_rows.hpp"

namespace deform {
namespace {

#if defined(DEFORM_SIMD_AVX2)
__attribute__((target("avx2"))) Eigen::Vector3d shellRotationAvx2(const Eigen::Vector3d* x,
                                                                  const Eigen::Vector3d* x0,
                                                                  const double* mass_kg, std::size_t n,
                                                                  const Eigen::Vector3d& core_m,
                                                                  const Eigen::Vector3d& shift_m) {
  __m256d sum = _mm256_setzero_pd();
  const Points4 core = broadcast4(core_m), shift = broadcast4(shift_m);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const Points4 p = loadRun4(x + i), p0 = loadRun4(x0 + i);
    // m (x0 - core) x (x - shift - x0)
    sum = addLaneRows(
        sum, times(_mm256_loadu_pd(mass_kg + i), cross4(minus(p0, core), minus(minus(p, shift), p0))));
  }
  Eigen::Vector3d g = vectorOf(sum);
  for (; i < n; ++i) g += mass_kg[i] * (x0[i] - core_m).cross(x[i] - shift_m - x0[i]);
  return g;
}

__attribute__((target("avx2"))) Eigen::Vector3d turnShellAvx2(Eigen::Vector3d* x, const Eigen::Vector3d* x0,
                                                              const double* mass_kg, std::size_t n,
                                                              const Eigen::Vector3d& core_m,
                                                              const Eigen::Vector3d& shift_m,
                                                              const Eigen::Vector3d& mu,
                                                              Eigen::Vector3d& push) {
  __m256d given_sum = _mm256_setzero_pd(), push_sum = rowOf(push);
  const Points4 core = broadcast4(core_m), shift = broadcast4(shift_m), turn = broadcast4(mu);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const Points4 p = loadRun4(x + i), p0 = loadRun4(x0 + i);
    const __m256d m = _mm256_loadu_pd(mass_kg + i);
    const Points4 dx = cross4(turn, minus(p0, core));
    given_sum = addLaneRows(given_sum, times(m, cross4(minus(minus(p, shift), core), dx)));
    storeRun4(plus(p, dx), x + i);
    push_sum = addLaneRows(push_sum, times(m, dx));
  }
  Eigen::Vector3d given = vectorOf(given_sum);
  push = vectorOf(push_sum);
  // The last points one at a time, into the same sums (turnShell's loop).
  for (; i < n; ++i) {
    const Eigen::Vector3d dx = mu.cross(x0[i] - core_m);
    given += mass_kg[i] * (x[i] - shift_m - core_m).cross(dx);
    x[i] += dx;
    push += mass_kg[i] * dx;
  }
  return given;
}
#endif

}  // namespace

Eigen::Vector3d shellRotationWide(const Eigen::Vector3d* x, const Eigen::Vector3d* x0, const double* mass_kg,
                                  std::size_t n, const Eigen::Vector3d& core_m,
                                  const Eigen::Vector3d& shift_m, bool wide) {
#if defined(DEFORM_SIMD_AVX2)
  if (wide && wideSweepAvailable()) return shellRotationAvx2(x, x0, mass_kg, n, core_m, shift_m);
#else
  (void)wide;
#endif
  return shellRotation(x, x0, mass_kg, n, core_m, shift_m);
}

Eigen::Vector3d turnShellWide(Eigen::Vector3d* x, const Eigen::Vector3d* x0, const double* mass_kg,
                              std::size_t n, const Eigen::Vector3d& core_m, const Eigen::Vector3d& shift_m,
                              const Eigen::Vector3d& mu, Eigen::Vector3d& push, bool wide) {
#if defined(DEFORM_SIMD_AVX2)
  if (wide && wideSweepAvailable()) return turnShellAvx2(x, x0, mass_kg, n, core_m, shift_m, mu, push);
#else
  (void)wide;
#endif
  return turnShell(x, x0, mass_kg, n, core_m, shift_m, mu, push);
}

}  // namespace deform
