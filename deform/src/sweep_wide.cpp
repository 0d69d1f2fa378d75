// The wide sweep of distance constraints, and the band test of their plasticity (sweep_wide.hpp).
#include "sweep_wide.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "simd_rows.hpp"

namespace deform {

std::vector<uint8_t> disjointRuns(const std::vector<uint32_t>& pairs) {
  const std::size_t n = pairs.size() / 2;
  std::vector<uint8_t> run(n, 0);
  if (n == 0) return run;
  // Two pointers: [k, end) is the longest run from k whose constraints share no point; `uses` counts each
  // point's constraints in it. A run from k + 1 reaches at least as far, so `end` never goes back.
  std::vector<uint8_t> uses(*std::max_element(pairs.begin(), pairs.end()) + std::size_t{1}, 0);
  std::size_t end = 0;
  for (std::size_t k = 0; k < n; ++k) {
    while (end < n && end - k < kLongestRun) {
      const uint32_t a = pairs[2 * end], b = pairs[2 * end + 1];
      if (a == b || uses[a] != 0 || uses[b] != 0) break;
      ++uses[a];
      ++uses[b];
      ++end;
    }
    run[k] = static_cast<uint8_t>(end - k);
    if (end > k) {
      --uses[pairs[2 * k]];
      --uses[pairs[2 * k + 1]];
    } else {
      end = k + 1;  // constraint k alone is no run (a == b): the next starts past it
    }
  }
  return run;
}

namespace {

// The records read as pairs of doubles four at a time (splitPairs4, simd_rows.hpp).
static_assert(sizeof(DistanceFactors) == 16 && offsetof(DistanceFactors, inverse_denominator) == 8);
static_assert(sizeof(ElasticBand) == 16 && offsetof(ElasticBand, longest_m2) == 8);

template <bool kLimited>
[[gnu::always_inline]] inline void projectOne(const DistanceSweep& s, std::size_t k) {
  const uint32_t a = s.pairs[2 * k], b = s.pairs[2 * k + 1];
  projectDistance(s.x[a], s.x[b], s.w[a], s.w[b], s.rest_m[k], s.factors[k], s.lambda[k],
                  kLimited ? -s.h2 * s.yield[k].stretch_N : -HUGE_VAL,
                  kLimited ? s.h2 * s.yield[k].shorten_N : HUGE_VAL);
}

#if defined(DEFORM_SIMD_AVX2)
__attribute__((target("avx2"))) inline Points4 loadPoints(const Eigen::Vector3d* x, const uint32_t* pairs,
                                                          int side) {
  return loadPoints4(x[pairs[side]], x[pairs[2 + side]], x[pairs[4 + side]], x[pairs[6 + side]]);
}

__attribute__((target("avx2"))) inline void storePoints(Eigen::Vector3d* x, const uint32_t* pairs, int side,
                                                        const Points4& p) {
  storePoints4(p, x[pairs[side]], x[pairs[2 + side]], x[pairs[4 + side]], x[pairs[6 + side]]);
}

/// `moved` in the live lanes, `p` in the others.
__attribute__((target("avx2"))) inline Points4 blendLive(const Points4& p, const Points4& moved,
                                                         __m256d live) {
  return {_mm256_blendv_pd(p.x, moved.x, live), _mm256_blendv_pd(p.y, moved.y, live),
          _mm256_blendv_pd(p.z, moved.z, live)};
}

/// The stages of four constraints' projection, each lane projectDistance's operations in its order.
struct Multipliers4 {
  __m256d lambda, next;  ///< before and after the projection
};

/// Constraints k .. k + 3 (disjoint): their points and lengths |x_a - x_b|.
__attribute__((target("avx2"))) inline __m256d measureFour(const DistanceSweep& s, std::size_t k, Points4& pa,
                                                           Points4& pb) {
  const uint32_t* pairs = s.pairs + 2 * k;
  pa = loadPoints(s.x, pairs, 0);
  pb = loadPoints(s.x, pairs, 1);
  const __m256d dx = _mm256_sub_pd(pa.x, pb.x), dy = _mm256_sub_pd(pa.y, pb.y),
                dz = _mm256_sub_pd(pa.z, pb.z);
  return _mm256_sqrt_pd(
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz)));
}

/// Their multipliers: lambda + (-c - alpha~ lambda) / (w_a + w_b + alpha~), clamped to the yield forces.
template <bool kLimited>
__attribute__((target("avx2"))) inline Multipliers4 multipliersFour(const DistanceSweep& s, std::size_t k,
                                                                    __m256d length) {
  const __m256d c = _mm256_sub_pd(length, _mm256_loadu_pd(s.rest_m + k));
  __m256d alpha, inverse;  // the factors (alpha~, 1 / denominator) of four constraints
  splitPairs4(&s.factors[k].alpha_tilde, alpha, inverse);
  const __m256d lambda = _mm256_loadu_pd(s.lambda + k);
  const __m256d negative_c = _mm256_xor_pd(c, _mm256_set1_pd(-0.0));
  __m256d next =
      _mm256_add_pd(lambda, _mm256_mul_pd(_mm256_sub_pd(negative_c, _mm256_mul_pd(alpha, lambda)), inverse));
  if constexpr (kLimited) {
    // The yield forces (float stretch, shorten) of four constraints; std::clamp(next, lo, hi).
    const __m256 yield = _mm256_loadu_ps(&s.yield[k].stretch_N);
    const __m256 split_yield = _mm256_permutevar8x32_ps(yield, _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7));
    const __m256d lo =
        _mm256_mul_pd(_mm256_set1_pd(-s.h2), _mm256_cvtps_pd(_mm256_castps256_ps128(split_yield)));
    const __m256d hi =
        _mm256_mul_pd(_mm256_set1_pd(s.h2), _mm256_cvtps_pd(_mm256_extractf128_ps(split_yield, 1)));
    next = _mm256_blendv_pd(next, hi, _mm256_cmp_pd(hi, next, _CMP_LT_OQ));
    next = _mm256_blendv_pd(next, lo, _mm256_cmp_pd(next, lo, _CMP_LT_OQ));
  }
  return {lambda, next};
}

/// projectDistance leaves a constraint untouched where length < kMinConstraintLength_m.
__attribute__((target("avx2"))) inline __m256d liveLanes(__m256d length) {
  return _mm256_cmp_pd(length, _mm256_set1_pd(kMinConstraintLength_m), _CMP_NLT_UQ);
}

/// Their points moved by the step `scale` = (next - lambda) / length (the live lanes).
__attribute__((target("avx2"))) inline void moveFour(const DistanceSweep& s, std::size_t k, __m256d length,
                                                     __m256d scale, Points4& pa, Points4& pb) {
  const uint32_t* pairs = s.pairs + 2 * k;
  // The inverse masses by scalar loads: AVX2's gather was slower here (paired, 4,000 points 4 x 1, 12.2
  // against 12.0 ns per constraint-iteration).
  const __m256d wa = _mm256_setr_pd(s.w[pairs[0]], s.w[pairs[2]], s.w[pairs[4]], s.w[pairs[6]]);
  const __m256d wb = _mm256_setr_pd(s.w[pairs[1]], s.w[pairs[3]], s.w[pairs[5]], s.w[pairs[7]]);
  const __m256d nx = _mm256_mul_pd(_mm256_sub_pd(pa.x, pb.x), scale),
                ny = _mm256_mul_pd(_mm256_sub_pd(pa.y, pb.y), scale),
                nz = _mm256_mul_pd(_mm256_sub_pd(pa.z, pb.z), scale);
  const Points4 a{_mm256_add_pd(pa.x, _mm256_mul_pd(wa, nx)), _mm256_add_pd(pa.y, _mm256_mul_pd(wa, ny)),
                  _mm256_add_pd(pa.z, _mm256_mul_pd(wa, nz))};
  const Points4 b{_mm256_sub_pd(pb.x, _mm256_mul_pd(wb, nx)), _mm256_sub_pd(pb.y, _mm256_mul_pd(wb, ny)),
                  _mm256_sub_pd(pb.z, _mm256_mul_pd(wb, nz))};
  const __m256d live = liveLanes(length);
  if (_mm256_movemask_pd(live) == 0xF) {  // all four live, nearly always
    pa = a;
    pb = b;
  } else {
    pa = blendLive(pa, a, live);
    pb = blendLive(pb, b, live);
  }
}

/// Four projected constraints, not yet stored.
struct Projected4 {
  Points4 a, b;
  __m256d lambda;
};

/// Constraints k .. k + 3 (disjoint), the stages one after the other.
template <bool kLimited>
__attribute__((target("avx2"))) inline Projected4 projectFourUnstored(const DistanceSweep& s, std::size_t k) {
  Projected4 p;
  const __m256d length = measureFour(s, k, p.a, p.b);
  const Multipliers4 l = multipliersFour<kLimited>(s, k, length);
  moveFour(s, k, length, _mm256_div_pd(_mm256_sub_pd(l.next, l.lambda), length), p.a, p.b);
  p.lambda = _mm256_blendv_pd(l.lambda, l.next, liveLanes(length));
  return p;
}

__attribute__((target("avx2"))) inline void store(const DistanceSweep& s, std::size_t k,
                                                  const Projected4& p) {
  _mm256_storeu_pd(s.lambda + k, p.lambda);
  storePoints(s.x, s.pairs + 2 * k, 0, p.a);
  storePoints(s.x, s.pairs + 2 * k, 1, p.b);
}

/// Fours in a run that shares no point, projected in stages.
constexpr std::size_t kStagedFours = 8;

/// Constraints k .. k + 4 kStagedFours - 1 (disjoint), each stage over all of them before the next: their
/// square roots, then their divisions, issue back to back instead of each four's waiting on its own
/// (paired, 4,000 points 4 x 1: the edges' sweep 0.7-0.8 of the eights' time). Only independent operations
/// change order (a multiplier is stored before the points of the fours before it), so the result is
/// projectFourUnstored's to the bit.
template <bool kLimited>
__attribute__((target("avx2"))) inline void projectStaged(const DistanceSweep& s, std::size_t k) {
  Points4 pa[kStagedFours], pb[kStagedFours];
  __m256d length[kStagedFours], scale[kStagedFours];
  for (std::size_t j = 0; j < kStagedFours; ++j) length[j] = measureFour(s, k + 4 * j, pa[j], pb[j]);
  for (std::size_t j = 0; j < kStagedFours; ++j) {
    const Multipliers4 l = multipliersFour<kLimited>(s, k + 4 * j, length[j]);
    _mm256_storeu_pd(s.lambda + k + 4 * j, _mm256_blendv_pd(l.lambda, l.next, liveLanes(length[j])));
    scale[j] = _mm256_sub_pd(l.next, l.lambda);
  }
  for (std::size_t j = 0; j < kStagedFours; ++j) scale[j] = _mm256_div_pd(scale[j], length[j]);
  for (std::size_t j = 0; j < kStagedFours; ++j) {
    moveFour(s, k + 4 * j, length[j], scale[j], pa[j], pb[j]);
    storePoints(s.x, s.pairs + 2 * (k + 4 * j), 0, pa[j]);
    storePoints(s.x, s.pairs + 2 * (k + 4 * j), 1, pb[j]);
  }
}

template <bool kLimited>
__attribute__((target("avx2"))) void sweepAvx2(const DistanceSweep& shared, std::size_t begin,
                                               std::size_t end) {
  const DistanceSweep s = shared;  // a local copy: the stores cannot alias its fields (prediction.cpp)
  std::size_t k = begin;
  while (k < end) {
    const std::size_t run = std::min<std::size_t>(s.disjoint[k], end - k);
    if (run >= 4 * kStagedFours) {
      projectStaged<kLimited>(s, k);
      k += 4 * kStagedFours;
    } else if (run >= 8) {
      // Two fours whose eight constraints share no point, both loaded before either is stored: their
      // square roots and divisions overlap.
      const Projected4 first = projectFourUnstored<kLimited>(s, k);
      const Projected4 second = projectFourUnstored<kLimited>(s, k + 4);
      store(s, k, first);
      store(s, k + 4, second);
      k += 8;
    } else if (run >= 4) {
      store(s, k, projectFourUnstored<kLimited>(s, k));
      k += 4;
    } else {
      projectOne<kLimited>(s, k);
      ++k;
    }
  }
}
#endif

}  // namespace

#if defined(DEFORM_SIMD_AVX2)
/// outsideBands over the whole fours of [begin, end); returns where they end (the rest is the caller's).
__attribute__((target("avx2"))) static std::size_t outsideBandsAvx2(
    const Eigen::Vector3d* x, const uint32_t* pairs, const ElasticBand* bands, std::size_t begin,
    std::size_t end, std::vector<uint32_t>& which, std::vector<double>& length_m2) {
  std::size_t k = begin;
  for (; k + 4 <= end; k += 4) {
    const uint32_t* p = pairs + 2 * k;
    const Points4 a = loadPoints(x, p, 0), b = loadPoints(x, p, 1);
    const __m256d dx = _mm256_sub_pd(a.x, b.x), dy = _mm256_sub_pd(a.y, b.y), dz = _mm256_sub_pd(a.z, b.z);
    const __m256d l2 =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
    // The bands (shortest, longest) of four constraints; holds: shortest < l2 < longest.
    __m256d shortest, longest;
    splitPairs4(&bands[k].shortest_m2, shortest, longest);
    const __m256d holds =
        _mm256_and_pd(_mm256_cmp_pd(l2, shortest, _CMP_GT_OQ), _mm256_cmp_pd(l2, longest, _CMP_LT_OQ));
    const int outside = ~_mm256_movemask_pd(holds) & 0xF;
    if (outside == 0) continue;
    alignas(32) double lane[4];
    _mm256_store_pd(lane, l2);
    for (int j = 0; j < 4; ++j)
      if (outside & (1 << j)) {
        which.push_back(static_cast<uint32_t>(k + j));
        length_m2.push_back(lane[j]);
      }
  }
  return k;
}
#endif

void outsideBands(const Eigen::Vector3d* x, const uint32_t* pairs, const ElasticBand* bands,
                  std::size_t begin, std::size_t end, bool wide, std::vector<uint32_t>& which,
                  std::vector<double>& length_m2) {
  std::size_t k = begin;
#if defined(DEFORM_SIMD_AVX2)
  if (wide && wideSweepAvailable()) k = outsideBandsAvx2(x, pairs, bands, begin, end, which, length_m2);
#else
  (void)wide;
#endif
  for (; k < end; ++k) {
    const double l2 = (x[pairs[2 * k]] - x[pairs[2 * k + 1]]).squaredNorm();
    if (bands[k].holds(l2)) continue;
    which.push_back(static_cast<uint32_t>(k));
    length_m2.push_back(l2);
  }
}

bool wideSweepAvailable() {
#if defined(DEFORM_SIMD_AVX2)
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

template <bool kLimited>
void sweepDistances(const DistanceSweep& sweep, std::size_t begin, std::size_t end, bool wide) {
#if defined(DEFORM_SIMD_AVX2)
  if (wide) {
    sweepAvx2<kLimited>(sweep, begin, end);
    return;
  }
#else
  (void)wide;
#endif
  for (std::size_t k = begin; k < end; ++k) projectOne<kLimited>(sweep, k);
}

template void sweepDistances<true>(const DistanceSweep&, std::size_t, std::size_t, bool);
template void sweepDistances<false>(const DistanceSweep&, std::size_t, std::size_t, bool);

}  // namespace deform
