// The shell orientation constraint's passes, four points at a time (shell_wide.hpp).
#include "shell_wide.hpp"

#include <deform/constraints.hpp>
#include <deform/solver_params.hpp>

#include "simd_rows.hpp"

namespace deform {
namespace {

#if defined(DEFORM_SIMD_AVX2)
/// Adds the four lanes of `v` to `sum` in lane order.
__attribute__((target("avx2"))) inline void addLanes(Eigen::Vector3d& sum, const Points4& v) {
  alignas(32) double px[4], py[4], pz[4];
  _mm256_store_pd(px, v.x);
  _mm256_store_pd(py, v.y);
  _mm256_store_pd(pz, v.z);
  for (int lane = 0; lane < 4; ++lane) sum += Eigen::Vector3d(px[lane], py[lane], pz[lane]);
}

__attribute__((target("avx2"))) Eigen::Vector3d shellRotationAvx2(const Eigen::Vector3d* x,
                                                                  const Eigen::Vector3d* x0,
                                                                  const double* mass_kg, std::size_t n,
                                                                  const Eigen::Vector3d& core_m,
                                                                  const Eigen::Vector3d& shift_m) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  const Points4 core = broadcast4(core_m), shift = broadcast4(shift_m);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const Points4 p = loadPoints4(x[i], x[i + 1], x[i + 2], x[i + 3]);
    const Points4 p0 = loadPoints4(x0[i], x0[i + 1], x0[i + 2], x0[i + 3]);
    // m (x0 - core) x (x - shift - x0)
    addLanes(g, times(_mm256_loadu_pd(mass_kg + i), cross4(minus(p0, core), minus(minus(p, shift), p0))));
  }
  for (; i < n; ++i) g += mass_kg[i] * (x0[i] - core_m).cross(x[i] - shift_m - x0[i]);
  return g;
}

__attribute__((target("avx2"))) Eigen::Vector3d turnShellAvx2(Eigen::Vector3d* x, const Eigen::Vector3d* x0,
                                                              const double* mass_kg, std::size_t n,
                                                              const Eigen::Vector3d& core_m,
                                                              const Eigen::Vector3d& shift_m,
                                                              const Eigen::Vector3d& mu,
                                                              Eigen::Vector3d& push) {
  Eigen::Vector3d given{0, 0, 0};
  const Points4 core = broadcast4(core_m), shift = broadcast4(shift_m), turn = broadcast4(mu);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const Points4 p = loadPoints4(x[i], x[i + 1], x[i + 2], x[i + 3]);
    const Points4 p0 = loadPoints4(x0[i], x0[i + 1], x0[i + 2], x0[i + 3]);
    const __m256d m = _mm256_loadu_pd(mass_kg + i);
    const Points4 dx = cross4(turn, minus(p0, core));
    addLanes(given, times(m, cross4(minus(minus(p, shift), core), dx)));
    storePoints4({_mm256_add_pd(p.x, dx.x), _mm256_add_pd(p.y, dx.y), _mm256_add_pd(p.z, dx.z)}, x[i],
                 x[i + 1], x[i + 2], x[i + 3]);
    addLanes(push, times(m, dx));
  }
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
