// The crush columns' sweep, one or four at a time (columns_wide.hpp).
#include "columns_wide.hpp"

#include <deform/solver_params.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "simd_rows.hpp"

namespace deform {
namespace {

// The records read as pairs of doubles four at a time (splitPairs4, simd_rows.hpp).
static_assert(sizeof(DistanceFactors) == 16 && offsetof(DistanceFactors, inverse_denominator) == 8);
static_assert(sizeof(YieldLimits) == 16 && offsetof(YieldLimits, shorten_m) == 8);
static_assert(sizeof(SpokeConstraint) == 16 && offsetof(SpokeConstraint, compliance_m_per_N) == 8);

/// The limit of column k on its multiplier `next` (projectColumn's Limit), as the sweep puts it.
inline double columnLimit(const ColumnSweep& s, std::size_t k, double to_lambda,
                          const Eigen::Vector3d& push) {
  // The column pushes along lambda: its point is displaced along -lambda.
  if (s.bottomed[k] && s.normals[k].dot(push) > 0) return HUGE_VAL;
  return to_lambda * columnYield_m(s.normals[k], -push, s.limits[k], s.taken_m[k]);
}

template <bool kLimited>
void sweepOne(const ColumnSweep& s, std::size_t j, ColumnReaction& out) {
  const std::size_t k = s.order[j];
  const SpokeConstraint& c = s.spokes[k];
  const uint32_t i = c.point;
  Eigen::Vector3d* x = s.x;
  const Eigen::Vector3d before = x[i];
  const Eigen::Vector3d& rest = s.rest_m[k];
  if constexpr (kLimited) {
    const double to_lambda = s.h2 / c.compliance_m_per_N;
    const bool bottomed = s.bottomed[k];
    projectColumn(
        x[i], rest + s.shift_m, s.w[i], s.factors[k], s.lambda[k],
        [&](const Eigen::Vector3d& push) { return columnLimit(s, k, to_lambda, push); },
        [&](const Eigen::Vector3d& next) {
          return columnSurelyWithinLimit(s.normals[k], next, s.limits[k], to_lambda, bottomed);
        });
  } else {
    projectColumn(x[i], rest + s.shift_m, s.w[i], s.factors[k], s.lambda[k], nullptr);
  }
  const Eigen::Vector3d pull = s.mass_kg[i] * (x[i] - before);
  out.pull += pull;
  out.twist += (rest - s.core_m).cross(pull);
}

template <bool kLimited>
void spokeOne(const SpokeSweep& s, std::size_t j, ColumnReaction& out) {
  const std::size_t k = s.order[j];
  const uint32_t i = s.spokes[k].point;
  Eigen::Vector3d* x = s.x;
  const Eigen::Vector3d before = x[i];
  // The anchor is a copy, left unmoved (inverse mass 0 here): the core takes the sweep's summed pull.
  Eigen::Vector3d anchor = s.core_m + s.anchors_m[k];
  projectDistance(x[i], anchor, s.w[i], 0.0, s.rest_m[k], s.factors[k], s.lambda[k],
                  kLimited ? -s.h2 * s.yield[k].stretch_N : -HUGE_VAL,
                  kLimited ? s.h2 * s.yield[k].shorten_N : HUGE_VAL);
  const Eigen::Vector3d pull = s.mass_kg[i] * (x[i] - before);
  out.pull += pull;
  out.twist += s.anchors_m[k].cross(pull);
}

#if defined(DEFORM_SIMD_AVX2)
/// One component of lambda + (-c - alpha lambda) inverse.
__attribute__((target("avx2"))) inline __m256d nextLambda(__m256d lambda, __m256d c, __m256d alpha,
                                                          __m256d inverse) {
  const __m256d negative_c = _mm256_xor_pd(c, _mm256_set1_pd(-0.0));
  return _mm256_add_pd(lambda,
                       _mm256_mul_pd(_mm256_sub_pd(negative_c, _mm256_mul_pd(alpha, lambda)), inverse));
}

/// The columns' reaction as two rows held in registers through a sweep: (pull x, y, z, twist x) and
/// (twist y, z).
struct ReactionRows {
  __m256d head;
  __m128d tail;
};

__attribute__((target("avx2"))) inline ReactionRows rowsOf(const ColumnReaction& r) {
  return {_mm256_setr_pd(r.pull.x(), r.pull.y(), r.pull.z(), r.twist.x()),
          _mm_setr_pd(r.twist.y(), r.twist.z())};
}

__attribute__((target("avx2"))) inline ColumnReaction reactionOf(const ReactionRows& rows) {
  alignas(32) double head[4], tail[2];
  _mm256_store_pd(head, rows.head);
  _mm_store_pd(tail, rows.tail);
  ColumnReaction r;
  r.pull = {head[0], head[1], head[2]};
  r.twist = {head[3], tail[0], tail[1]};
  return r;
}

/// Adds the reaction of four corrections, lane by lane in the sweep's order: each lane's row added in turn,
/// so every component takes its four terms in lane order (as ColumnReaction's one-at-a-time sums).
__attribute__((target("avx2"))) inline void addReaction(const Points4& pull, const Points4& twist,
                                                        ReactionRows& out) {
  // The 4 x 4 of (pull x, y, z, twist x) transposed: row `lane` holds that lane's four.
  const __m256d xy02 = _mm256_unpacklo_pd(pull.x, pull.y);   // px0 py0 px2 py2
  const __m256d xy13 = _mm256_unpackhi_pd(pull.x, pull.y);   // px1 py1 px3 py3
  const __m256d zt02 = _mm256_unpacklo_pd(pull.z, twist.x);  // pz0 tx0 pz2 tx2
  const __m256d zt13 = _mm256_unpackhi_pd(pull.z, twist.x);  // pz1 tx1 pz3 tx3
  // (twist y, z) of each lane.
  const __m256d yz02 = _mm256_unpacklo_pd(twist.y, twist.z);  // ty0 tz0 ty2 tz2
  const __m256d yz13 = _mm256_unpackhi_pd(twist.y, twist.z);  // ty1 tz1 ty3 tz3
  out.head = _mm256_add_pd(out.head, _mm256_permute2f128_pd(xy02, zt02, 0x20));
  out.head = _mm256_add_pd(out.head, _mm256_permute2f128_pd(xy13, zt13, 0x20));
  out.head = _mm256_add_pd(out.head, _mm256_permute2f128_pd(xy02, zt02, 0x31));
  out.head = _mm256_add_pd(out.head, _mm256_permute2f128_pd(xy13, zt13, 0x31));
  out.tail = _mm_add_pd(out.tail, _mm256_castpd256_pd128(yz02));
  out.tail = _mm_add_pd(out.tail, _mm256_castpd256_pd128(yz13));
  out.tail = _mm_add_pd(out.tail, _mm256_extractf128_pd(yz02, 1));
  out.tail = _mm_add_pd(out.tail, _mm256_extractf128_pd(yz13, 1));
}

/// Four values of an array at the indices k, or from k[0] on where kRun (k[l] = k[0] + l).
template <bool kRun>
__attribute__((target("avx2"))) inline __m256d doubles4(const double* a, const std::size_t (&k)[4]) {
  if constexpr (kRun) return _mm256_loadu_pd(a + k[0]);
  return _mm256_setr_pd(a[k[0]], a[k[1]], a[k[2]], a[k[3]]);
}
template <bool kRun>
__attribute__((target("avx2"))) inline Points4 points4(const Eigen::Vector3d* a, const std::size_t (&k)[4]) {
  if constexpr (kRun) return loadRun4(a + k[0]);
  return loadPoints4(a[k[0]], a[k[1]], a[k[2]], a[k[3]]);
}
template <bool kRun>
__attribute__((target("avx2"))) inline void storePoints(const Points4& p, Eigen::Vector3d* a,
                                                        const std::size_t (&k)[4]) {
  if constexpr (kRun)
    storeRun4(p, a + k[0]);
  else
    storePoints4(p, a[k[0]], a[k[1]], a[k[2]], a[k[3]]);
}

/// Spokes order[j .. j + 3], each lane spokeOne's operations in their order.
template <bool kLimited>
__attribute__((target("avx2"))) inline void spokesFour(const SpokeSweep& s, std::size_t j,
                                                       ReactionRows& out) {
  const std::size_t k[4] = {s.order[j], s.order[j + 1], s.order[j + 2], s.order[j + 3]};
  const uint32_t i[4] = {s.spokes[k[0]].point, s.spokes[k[1]].point, s.spokes[k[2]].point,
                         s.spokes[k[3]].point};
  Eigen::Vector3d* x = s.x;
  const Points4 before = loadPoints4(x[i[0]], x[i[1]], x[i[2]], x[i[3]]);
  const Points4 arm = loadPoints4(s.anchors_m[k[0]], s.anchors_m[k[1]], s.anchors_m[k[2]], s.anchors_m[k[3]]);
  const Points4 d = minus(before, plus(broadcast4(s.core_m), arm));
  const __m256d length = _mm256_sqrt_pd(dot4(d, d));
  const __m256d live = _mm256_cmp_pd(length, _mm256_set1_pd(kMinConstraintLength_m), _CMP_NLT_UQ);
  const __m256d c =
      _mm256_sub_pd(length, _mm256_setr_pd(s.rest_m[k[0]], s.rest_m[k[1]], s.rest_m[k[2]], s.rest_m[k[3]]));
  const __m256d alpha = _mm256_setr_pd(s.factors[k[0]].alpha_tilde, s.factors[k[1]].alpha_tilde,
                                       s.factors[k[2]].alpha_tilde, s.factors[k[3]].alpha_tilde);
  const __m256d inverse =
      _mm256_setr_pd(s.factors[k[0]].inverse_denominator, s.factors[k[1]].inverse_denominator,
                     s.factors[k[2]].inverse_denominator, s.factors[k[3]].inverse_denominator);
  const __m256d lambda = _mm256_setr_pd(s.lambda[k[0]], s.lambda[k[1]], s.lambda[k[2]], s.lambda[k[3]]);
  __m256d next = nextLambda(lambda, c, alpha, inverse);
  if constexpr (kLimited) {
    // std::clamp(next, -h^2 F_stretch, h^2 F_shorten), the yield forces in float.
    const __m256d lo = _mm256_mul_pd(_mm256_set1_pd(-s.h2),
                                     _mm256_setr_pd(s.yield[k[0]].stretch_N, s.yield[k[1]].stretch_N,
                                                    s.yield[k[2]].stretch_N, s.yield[k[3]].stretch_N));
    const __m256d hi =
        _mm256_mul_pd(_mm256_set1_pd(s.h2), _mm256_setr_pd(s.yield[k[0]].shorten_N, s.yield[k[1]].shorten_N,
                                                           s.yield[k[2]].shorten_N, s.yield[k[3]].shorten_N));
    next = _mm256_blendv_pd(next, hi, _mm256_cmp_pd(hi, next, _CMP_LT_OQ));
    next = _mm256_blendv_pd(next, lo, _mm256_cmp_pd(next, lo, _CMP_LT_OQ));
  }
  const __m256d scale = _mm256_div_pd(_mm256_sub_pd(next, lambda), length);
  const __m256d w = _mm256_setr_pd(s.w[i[0]], s.w[i[1]], s.w[i[2]], s.w[i[3]]);
  const Points4 moved = plus(before, times(w, times(scale, d)));
  const Points4 after{_mm256_blendv_pd(before.x, moved.x, live), _mm256_blendv_pd(before.y, moved.y, live),
                      _mm256_blendv_pd(before.z, moved.z, live)};
  storePoints4(after, x[i[0]], x[i[1]], x[i[2]], x[i[3]]);
  alignas(32) double stored[4];
  _mm256_store_pd(stored, _mm256_blendv_pd(lambda, next, live));
  for (int lane = 0; lane < 4; ++lane) s.lambda[k[lane]] = stored[lane];
  const __m256d m = _mm256_setr_pd(s.mass_kg[i[0]], s.mass_kg[i[1]], s.mass_kg[i[2]], s.mass_kg[i[3]]);
  const Points4 pull = times(m, minus(after, before));
  addReaction(pull, cross4(arm, pull), out);
}

/// Columns order[j .. j + 3], each lane sweepOne's operations in their order. kRun: they are columns
/// k .. k + 3 of points k .. k + 3 (ColumnSweep::points_in_order), read and written by whole rows.
template <bool kLimited, bool kRun>
__attribute__((target("avx2"))) inline void sweepFour(const ColumnSweep& s, std::size_t j,
                                                      ReactionRows& out) {
  const std::size_t k[4] = {s.order[j], s.order[j + 1], s.order[j + 2], s.order[j + 3]};
  std::size_t i[4];
  for (int lane = 0; lane < 4; ++lane) i[lane] = kRun ? k[lane] : s.spokes[k[lane]].point;
  Eigen::Vector3d* x = s.x;
  const Points4 before = points4<kRun>(x, i);
  const Points4 rest = points4<kRun>(s.rest_m, k);
  const Points4 lambda = points4<kRun>(s.lambda, k);
  __m256d alpha, inverse;
  if constexpr (kRun) {
    splitPairs4(&s.factors[k[0]].alpha_tilde, alpha, inverse);
  } else {
    alpha = _mm256_setr_pd(s.factors[k[0]].alpha_tilde, s.factors[k[1]].alpha_tilde,
                           s.factors[k[2]].alpha_tilde, s.factors[k[3]].alpha_tilde);
    inverse = _mm256_setr_pd(s.factors[k[0]].inverse_denominator, s.factors[k[1]].inverse_denominator,
                             s.factors[k[2]].inverse_denominator, s.factors[k[3]].inverse_denominator);
  }
  // c = x - (rest + shift); next = lambda + (-c - alpha lambda) / (w + w_core + alpha).
  const Points4 c = minus(before, plus(rest, broadcast4(s.shift_m)));
  const __m256d sign = _mm256_set1_pd(-0.0);
  Points4 next{nextLambda(lambda.x, c.x, alpha, inverse), nextLambda(lambda.y, c.y, alpha, inverse),
               nextLambda(lambda.z, c.z, alpha, inverse)};
  if constexpr (kLimited) {
    const Points4 normal = points4<kRun>(s.normals, k);
    __m256d compliance, stretch, shorten, bottomed;
    if constexpr (kRun) {
      __m256d point_and_material;
      splitPairs4(reinterpret_cast<const double*>(&s.spokes[k[0]]), point_and_material, compliance);
      splitPairs4(&s.limits[k[0]].stretch_m, stretch, shorten);
      uint32_t four_bytes;
      std::memcpy(&four_bytes, s.bottomed + k[0], sizeof four_bytes);
      const __m256i flags = _mm256_cvtepu8_epi64(_mm_cvtsi32_si128(static_cast<int>(four_bytes)));
      bottomed = _mm256_castsi256_pd(
          _mm256_xor_si256(_mm256_cmpeq_epi64(flags, _mm256_setzero_si256()), _mm256_set1_epi64x(-1)));
    } else {
      compliance = _mm256_setr_pd(s.spokes[k[0]].compliance_m_per_N, s.spokes[k[1]].compliance_m_per_N,
                                  s.spokes[k[2]].compliance_m_per_N, s.spokes[k[3]].compliance_m_per_N);
      stretch = _mm256_setr_pd(s.limits[k[0]].stretch_m, s.limits[k[1]].stretch_m, s.limits[k[2]].stretch_m,
                               s.limits[k[3]].stretch_m);
      shorten = _mm256_setr_pd(s.limits[k[0]].shorten_m, s.limits[k[1]].shorten_m, s.limits[k[2]].shorten_m,
                               s.limits[k[3]].shorten_m);
      bottomed = _mm256_castsi256_pd(
          _mm256_setr_epi64x(-int64_t{s.bottomed[k[0]] != 0}, -int64_t{s.bottomed[k[1]] != 0},
                             -int64_t{s.bottomed[k[2]] != 0}, -int64_t{s.bottomed[k[3]] != 0}));
    }
    const __m256d to_lambda = _mm256_div_pd(_mm256_set1_pd(s.h2), compliance);
    // columnSurelyWithinLimit, lane by lane.
    const __m256d along = dot4(normal, next);
    const __m256d pushing_in = _mm256_cmp_pd(along, _mm256_setzero_pd(), _CMP_GT_OQ);
    const __m256d yield_m = _mm256_blendv_pd(stretch, shorten, pushing_in);
    const __m256d magnitude2 = _mm256_mul_pd(dot4(next, next), _mm256_set1_pd(1 + kSurelyMargin));
    const __m256d bound =
        _mm256_mul_pd(_mm256_mul_pd(to_lambda, yield_m), _mm256_andnot_pd(sign, along));  // |along|
    const __m256d within =
        _mm256_or_pd(_mm256_and_pd(bottomed, pushing_in), _mm256_cmp_pd(magnitude2, bound, _CMP_LE_OQ));
    const int beyond = ~_mm256_movemask_pd(within) & 0xF;
    if (beyond != 0) {
      // The lanes not surely within: projectColumn's limit, one at a time.
      alignas(32) double nx[4], ny[4], nz[4], tl[4];
      _mm256_store_pd(nx, next.x);
      _mm256_store_pd(ny, next.y);
      _mm256_store_pd(nz, next.z);
      _mm256_store_pd(tl, to_lambda);
      for (int lane = 0; lane < 4; ++lane) {
        if (!(beyond & (1 << lane))) continue;
        Eigen::Vector3d n(nx[lane], ny[lane], nz[lane]);
        const double length = n.norm();
        if (length > 0) {
          const double limit = columnLimit(s, k[lane], tl[lane], n / length);
          if (length > limit) n *= limit / length;
        }
        nx[lane] = n.x();
        ny[lane] = n.y();
        nz[lane] = n.z();
      }
      next = {_mm256_load_pd(nx), _mm256_load_pd(ny), _mm256_load_pd(nz)};
    }
  }
  const Points4 after = plus(before, times(doubles4<kRun>(s.w, i), minus(next, lambda)));
  storePoints<kRun>(after, x, i);
  storePoints<kRun>(next, s.lambda, k);
  const Points4 pull = times(doubles4<kRun>(s.mass_kg, i), minus(after, before));
  addReaction(pull, cross4(minus(rest, broadcast4(s.core_m)), pull), out);
}

template <bool kLimited>
__attribute__((target("avx2"))) void spokesAvx2(const SpokeSweep& shared, std::size_t begin, std::size_t end,
                                                ColumnReaction& out) {
  const SpokeSweep s = shared;      // a local copy: the stores cannot alias its fields (prediction.cpp)
  ReactionRows rows = rowsOf(out);  // in registers through the loop
  std::size_t j = begin;
  for (; j + 4 <= end; j += 4) spokesFour<kLimited>(s, j, rows);
  out = reactionOf(rows);
  for (; j < end; ++j) spokeOne<kLimited>(s, j, out);
}

/// columnsNotSurelyElastic over the whole fours of [begin, end); returns where they end.
__attribute__((target("avx2"))) std::size_t notSurelyElasticAvx2(
    const Eigen::Vector3d* x, const SpokeConstraint* spokes, const Eigen::Vector3d* rest_m,
    const Eigen::Vector3d* normals, const YieldLimits* limits, const Eigen::Vector3d& shift_m,
    std::size_t begin, std::size_t end, std::vector<uint32_t>& which) {
  const Points4 shift = broadcast4(shift_m);
  const __m256d margin = _mm256_set1_pd(1 + kSurelyMargin), sign = _mm256_set1_pd(-0.0);
  std::size_t k = begin;
  for (; k + 4 <= end; k += 4) {
    const uint32_t first = spokes[k].point;
    const bool in_a_row = spokes[k + 1].point == first + 1 && spokes[k + 2].point == first + 2 &&
                          spokes[k + 3].point == first + 3;
    const Points4 p = in_a_row ? loadRun4(x + first)
                               : loadPoints4(x[first], x[spokes[k + 1].point], x[spokes[k + 2].point],
                                             x[spokes[k + 3].point]);
    const Points4 elastic = minus(minus(p, shift), loadRun4(rest_m + k));
    const __m256d along = dot4(loadRun4(normals + k), elastic);
    __m256d stretch, shorten;  // the limits of four columns
    splitPairs4(&limits[k].stretch_m, stretch, shorten);
    const __m256d yield_m =
        _mm256_blendv_pd(stretch, shorten, _mm256_cmp_pd(along, _mm256_setzero_pd(), _CMP_LT_OQ));
    const __m256d surely = _mm256_cmp_pd(_mm256_mul_pd(dot4(elastic, elastic), margin),
                                         _mm256_mul_pd(yield_m, _mm256_andnot_pd(sign, along)), _CMP_LE_OQ);
    const int not_surely = ~_mm256_movemask_pd(surely) & 0xF;
    for (int lane = 0; lane < 4; ++lane)
      if (not_surely & (1 << lane)) which.push_back(static_cast<uint32_t>(k + lane));
  }
  return k;
}

template <bool kLimited>
__attribute__((target("avx2"))) void sweepAvx2(const ColumnSweep& shared, std::size_t begin, std::size_t end,
                                               ColumnReaction& out) {
  const ColumnSweep s = shared;     // a local copy: the stores cannot alias its fields (prediction.cpp)
  ReactionRows rows = rowsOf(out);  // in registers through the loop
  std::size_t j = begin;
  for (; j + 4 <= end; j += 4) {
    const std::size_t k = s.order[j];
    if (s.points_in_order && s.order[j + 1] == k + 1 && s.order[j + 2] == k + 2 && s.order[j + 3] == k + 3)
      sweepFour<kLimited, true>(s, j, rows);
    else
      sweepFour<kLimited, false>(s, j, rows);
  }
  out = reactionOf(rows);
  for (; j < end; ++j) sweepOne<kLimited>(s, j, out);
}
#endif

}  // namespace

void columnsNotSurelyElastic(const Eigen::Vector3d* x, const SpokeConstraint* spokes,
                             const Eigen::Vector3d* rest_m, const Eigen::Vector3d* normals,
                             const YieldLimits* limits, const Eigen::Vector3d& shift_m, std::size_t begin,
                             std::size_t end, bool wide, std::vector<uint32_t>& which) {
  std::size_t k = begin;
#if defined(DEFORM_SIMD_AVX2)
  if (wide && wideSweepAvailable())
    k = notSurelyElasticAvx2(x, spokes, rest_m, normals, limits, shift_m, begin, end, which);
#else
  (void)wide;
#endif
  for (; k < end; ++k)
    if (!columnSurelyElastic(normals[k], x[spokes[k].point] - shift_m - rest_m[k], limits[k]))
      which.push_back(static_cast<uint32_t>(k));
}

template <bool kLimited>
void sweepColumns(const ColumnSweep& s, std::size_t begin, std::size_t end, bool wide, ColumnReaction& out) {
#if defined(DEFORM_SIMD_AVX2)
  if (wide && wideSweepAvailable()) {
    sweepAvx2<kLimited>(s, begin, end, out);
    return;
  }
#else
  (void)wide;
#endif
  for (std::size_t j = begin; j < end; ++j) sweepOne<kLimited>(s, j, out);
}

template <bool kLimited>
void sweepSpokes(const SpokeSweep& s, std::size_t begin, std::size_t end, bool wide, ColumnReaction& out) {
#if defined(DEFORM_SIMD_AVX2)
  if (wide && wideSweepAvailable()) {
    spokesAvx2<kLimited>(s, begin, end, out);
    return;
  }
#else
  (void)wide;
#endif
  for (std::size_t j = begin; j < end; ++j) spokeOne<kLimited>(s, j, out);
}

template void sweepSpokes<true>(const SpokeSweep&, std::size_t, std::size_t, bool, ColumnReaction&);
template void sweepSpokes<false>(const SpokeSweep&, std::size_t, std::size_t, bool, ColumnReaction&);
template void sweepColumns<true>(const ColumnSweep&, std::size_t, std::size_t, bool, ColumnReaction&);
template void sweepColumns<false>(const ColumnSweep&, std::size_t, std::size_t, bool, ColumnReaction&);

}  // namespace deform
