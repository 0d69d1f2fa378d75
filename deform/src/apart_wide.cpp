// SurelyApart's list of the points near a shape, one point at a time or four side by side
// (contact_shapes.hpp).
#include <deform/contact_shapes.hpp>
#include <deform/solver_params.hpp>

#include "simd_rows.hpp"

namespace deform {

#if defined(DEFORM_SIMD_AVX2)
namespace {

/// The lanes of four points that the test calls apart: n . x - offset > limit (a plane) or
/// |x - centre|^2 > limit (a ball), each with operator()'s operations in its order.
__attribute__((target("avx2"))) inline int apartLanes(const Points4& p, bool plane,
                                                      const Points4& normal_or_centre, __m256d offset,
                                                      __m256d limit) {
  if (plane)
    return _mm256_movemask_pd(
        _mm256_cmp_pd(_mm256_sub_pd(dot4(normal_or_centre, p), offset), limit, _CMP_GT_OQ));
  const Points4 d = minus(p, normal_or_centre);
  return _mm256_movemask_pd(_mm256_cmp_pd(dot4(d, d), limit, _CMP_GT_OQ));
}

/// listNear over the whole fours of [begin, end); returns where they end.
__attribute__((target("avx2"))) std::size_t listNearAvx2(const Eigen::Vector3d* points_m, std::size_t begin,
                                                         std::size_t end, bool plane,
                                                         const Eigen::Vector3d& normal_or_centre,
                                                         double offset_m, double limit,
                                                         std::vector<uint32_t>& near) {
  const Points4 shape = broadcast4(normal_or_centre);
  const __m256d offset = _mm256_set1_pd(offset_m), bound = _mm256_set1_pd(limit);
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) {
    const int apart = apartLanes(loadRun4(points_m + i), plane, shape, offset, bound);
    if (apart == 0xF) continue;
    for (int lane = 0; lane < 4; ++lane)
      if (!(apart & (1 << lane))) near.push_back(static_cast<uint32_t>(i + static_cast<std::size_t>(lane)));
  }
  return i;
}

}  // namespace
#endif

void SurelyApart::listNear(const Eigen::Vector3d* points_m, std::size_t begin, std::size_t end, bool wide,
                           std::vector<uint32_t>& near) const {
  std::size_t i = begin;
#if defined(DEFORM_SIMD_AVX2)
  if (wide && kind_ != Kind::Unsure && wideSweepAvailable())
    i = listNearAvx2(points_m, begin, end, kind_ == Kind::Plane, normal_or_centre_, offset_m_, limit_, near);
#else
  (void)wide;
#endif
  for (; i < end; ++i)
    if (!(*this)(points_m[i])) near.push_back(static_cast<uint32_t>(i));
}

}  // namespace deform
