// The visual constraint's near list, one point at a time or four side by side (cap_wide.hpp).
#include "cap_wide.hpp"

#include <deform/solver_params.hpp>

#include "simd_rows.hpp"

namespace deform {
namespace {

/// Whether point i may reach past its reduced cap (listNearCaps), one at a time.
inline bool nearCap(const Eigen::Vector3d* x, const Eigen::Vector3d* rest_m, const double* max_deviation_m,
                    const Eigen::Vector3d& core_m, const Eigen::Vector3d& core_rest_m, double reduced_by_m,
                    std::size_t i) {
  const double reach = max_deviation_m[i] - reduced_by_m;
  const Eigen::Vector3d d = x[i] - (rest_m[i] + core_m - core_rest_m);
  return reach <= 0 || !(d.squaredNorm() <= reach * reach);
}

#if defined(DEFORM_SIMD_AVX2)
/// listNearCaps over the whole fours of [begin, end); returns where they end.
__attribute__((target("avx2"))) std::size_t listNearCapsAvx2(
    const Eigen::Vector3d* x, const Eigen::Vector3d* rest_m, const double* max_deviation_m,
    const Eigen::Vector3d& core_m, const Eigen::Vector3d& core_rest_m, double reduced_by_m, std::size_t begin,
    std::size_t end, std::vector<uint32_t>& near) {
  const Points4 core = broadcast4(core_m), core_rest = broadcast4(core_rest_m);
  const __m256d reduced_by = _mm256_set1_pd(reduced_by_m), zero = _mm256_setzero_pd();
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) {
    // x - ((rest + core) - core_rest), as Eigen evaluates it component by component.
    const Points4 d = minus(loadRun4(x + i), minus(plus(loadRun4(rest_m + i), core), core_rest));
    const __m256d reach = _mm256_sub_pd(_mm256_loadu_pd(max_deviation_m + i), reduced_by);
    const __m256d within =
        _mm256_andnot_pd(_mm256_cmp_pd(reach, zero, _CMP_LE_OQ),
                         _mm256_cmp_pd(dot4(d, d), _mm256_mul_pd(reach, reach), _CMP_LE_OQ));
    const int listed = ~_mm256_movemask_pd(within) & 0xF;
    if (listed == 0) continue;
    for (int lane = 0; lane < 4; ++lane)
      if (listed & (1 << lane)) near.push_back(static_cast<uint32_t>(i + static_cast<std::size_t>(lane)));
  }
  return i;
}
#endif

}  // namespace

void listNearCaps(const Eigen::Vector3d* x, const Eigen::Vector3d* rest_m, const double* max_deviation_m,
                  const Eigen::Vector3d& core_m, const Eigen::Vector3d& core_rest_m, double reduced_by_m,
                  std::size_t begin, std::size_t end, bool wide, std::vector<uint32_t>& near) {
  std::size_t i = begin;
#if defined(DEFORM_SIMD_AVX2)
  if (wide && wideSweepAvailable())
    i = listNearCapsAvx2(x, rest_m, max_deviation_m, core_m, core_rest_m, reduced_by_m, begin, end, near);
#else
  (void)wide;
#endif
  for (; i < end; ++i)
    if (nearCap(x, rest_m, max_deviation_m, core_m, core_rest_m, reduced_by_m, i))
      near.push_back(static_cast<uint32_t>(i));
}

}  // namespace deform
