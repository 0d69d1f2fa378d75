// The support of a point set, one point at a time or four side by side (support_wide.hpp).
#include "support_wide.hpp"

#include <deform/solver_params.hpp>

#include "simd_rows.hpp"

namespace deform {
namespace {

std::size_t farthestOneByOne(const Eigen::Vector3d* points, std::size_t n, const Eigen::Vector3d& direction) {
  std::size_t best = 0;
  double best_dot = points[0].dot(direction);
  for (std::size_t i = 1; i < n; ++i) {
    const double d = points[i].dot(direction);
    if (d > best_dot) best_dot = d, best = i;
  }
  return best;
}

#if defined(DEFORM_SIMD_AVX2)
/// Each lane keeps the first largest product of its own points (i = lane mod 4), which is the scan's
/// order within the lane; the lanes' bests then go to the largest, the lowest index on a tie, and the
/// points past the last four follow one at a time. With every product finite that is the scan's answer.
/// Returns n when a product is not finite (the caller scans one at a time).
__attribute__((target("avx2"))) std::size_t farthestAvx2(const Eigen::Vector3d* points, std::size_t n,
                                                         const Eigen::Vector3d& direction) {
  const Points4 along = broadcast4(direction);
  __m256d best = dot4(loadRun4(points), along);
  __m256i best_index = _mm256_setr_epi64x(0, 1, 2, 3);
  __m256d finite = _mm256_cmp_pd(_mm256_sub_pd(best, best), _mm256_setzero_pd(), _CMP_EQ_OQ);
  const __m256i four = _mm256_set1_epi64x(4);
  __m256i index = best_index;
  std::size_t i = 4;
  for (; i + 4 <= n; i += 4) {
    index = _mm256_add_epi64(index, four);
    const __m256d d = dot4(loadRun4(points + i), along);
    finite = _mm256_and_pd(finite, _mm256_cmp_pd(_mm256_sub_pd(d, d), _mm256_setzero_pd(), _CMP_EQ_OQ));
    const __m256d larger = _mm256_cmp_pd(d, best, _CMP_GT_OQ);
    best = _mm256_blendv_pd(best, d, larger);
    best_index = _mm256_castpd_si256(
        _mm256_blendv_pd(_mm256_castsi256_pd(best_index), _mm256_castsi256_pd(index), larger));
  }
  if (_mm256_movemask_pd(finite) != 0xF) return n;
  alignas(32) double lane_best[4];
  alignas(32) int64_t lane_index[4];
  _mm256_store_pd(lane_best, best);
  _mm256_store_si256(reinterpret_cast<__m256i*>(lane_index), best_index);
  double best_dot = lane_best[0];
  std::size_t found = static_cast<std::size_t>(lane_index[0]);
  for (int lane = 1; lane < 4; ++lane) {
    const auto at = static_cast<std::size_t>(lane_index[lane]);
    if (lane_best[lane] > best_dot || (lane_best[lane] == best_dot && at < found)) {
      best_dot = lane_best[lane];
      found = at;
    }
  }
  for (; i < n; ++i) {
    const double d = points[i].dot(direction);
    if (!(d - d == 0)) return n;
    if (d > best_dot) best_dot = d, found = i;
  }
  return found;
}
#endif

}  // namespace

std::size_t farthestAlong(const Eigen::Vector3d* points, std::size_t n, const Eigen::Vector3d& direction,
                          bool wide) {
#if defined(DEFORM_SIMD_AVX2)
  if (wide && n >= 8 && wideSweepAvailable()) {
    const std::size_t found = farthestAvx2(points, n, direction);
    if (found < n) return found;
  }
#else
  (void)wide;
#endif
  return farthestOneByOne(points, n, direction);
}

}  // namespace deform
