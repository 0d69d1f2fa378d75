#pragma once
// Four points of an array of Eigen::Vector3d as three AVX2 columns (x, y, z of each in its lane) and back,
// for the four-wide passes (sweep_wide.cpp, columns_wide.cpp, prediction.cpp and others). Four points
// anywhere (loadPoints4) are read as they are written, (x, y) then z: a load spanning two earlier stores
// would wait for them to retire instead of taking their data. Four points in a row (loadRun4, storeRun4) are
// read and written as three rows of four coordinates, by the passes that go through the points in order and
// whose points were last written a whole pass before.
#include <Eigen/Core>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define DEFORM_SIMD_AVX2 1

namespace deform {

/// Four points' coordinates, one point per lane.
struct Points4 {
  __m256d x, y, z;
};

/// A point as a row (x, y, z, 0).
__attribute__((target("avx2"))) inline __m256d pointRow(const Eigen::Vector3d& p) {
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p.data())), _mm_load_sd(p.data() + 2), 1);
}

/// The points p0 .. p3 in lanes 0 .. 3.
__attribute__((target("avx2"))) inline Points4 loadPoints4(const Eigen::Vector3d& p0,
                                                           const Eigen::Vector3d& p1,
                                                           const Eigen::Vector3d& p2,
                                                           const Eigen::Vector3d& p3) {
  const __m256d r0 = pointRow(p0), r1 = pointRow(p1), r2 = pointRow(p2), r3 = pointRow(p3);
  const __m256d t0 = _mm256_unpacklo_pd(r0, r1);  // x0 x1 z0 z1
  const __m256d t1 = _mm256_unpackhi_pd(r0, r1);  // y0 y1 .. ..
  const __m256d t2 = _mm256_unpacklo_pd(r2, r3);  // x2 x3 z2 z3
  const __m256d t3 = _mm256_unpackhi_pd(r2, r3);  // y2 y3 .. ..
  return {_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_permute2f128_pd(t1, t3, 0x20),
          _mm256_permute2f128_pd(t0, t2, 0x31)};
}

/// Lanes 0 .. 3 of `p` into q0 .. q3.
__attribute__((target("avx2"))) inline void storePoints4(const Points4& p, Eigen::Vector3d& q0,
                                                         Eigen::Vector3d& q1, Eigen::Vector3d& q2,
                                                         Eigen::Vector3d& q3) {
  const __m256d xy02 = _mm256_unpacklo_pd(p.x, p.y);  // x0 y0 x2 y2
  const __m256d xy13 = _mm256_unpackhi_pd(p.x, p.y);  // x1 y1 x3 y3
  const __m128d z01 = _mm256_castpd256_pd128(p.z), z23 = _mm256_extractf128_pd(p.z, 1);
  _mm_storeu_pd(q0.data(), _mm256_castpd256_pd128(xy02));
  _mm_storeu_pd(q1.data(), _mm256_castpd256_pd128(xy13));
  _mm_storeu_pd(q2.data(), _mm256_extractf128_pd(xy02, 1));
  _mm_storeu_pd(q3.data(), _mm256_extractf128_pd(xy13, 1));
  _mm_store_sd(q0.data() + 2, z01);
  _mm_storeh_pd(q1.data() + 2, z01);
  _mm_store_sd(q2.data() + 2, z23);
  _mm_storeh_pd(q3.data() + 2, z23);
}

/// The four consecutive points p[0] .. p[3] in lanes 0 .. 3: three loads of four coordinates each,
/// [x0 y0 z0 x1] [y1 z1 x2 y2] [z2 x3 y3 z3], sorted into columns.
__attribute__((target("avx2"))) inline Points4 loadRun4(const Eigen::Vector3d* p) {
  const double* d = p->data();
  const __m256d a = _mm256_loadu_pd(d), b = _mm256_loadu_pd(d + 4), c = _mm256_loadu_pd(d + 8);
  const __m256d xy02 = _mm256_blend_pd(a, b, 0b1100);       // x0 y0 x2 y2
  const __m256d zx13 = _mm256_permute2f128_pd(a, c, 0x21);  // z0 x1 z2 x3
  const __m256d yz13 = _mm256_blend_pd(b, c, 0b1100);       // y1 z1 y3 z3
  return {_mm256_shuffle_pd(xy02, zx13, 0b1010), _mm256_shuffle_pd(xy02, yz13, 0b0101),
          _mm256_shuffle_pd(zx13, yz13, 0b1010)};
}

/// Lanes 0 .. 3 of `p` into the four consecutive points q[0] .. q[3] (loadRun4's inverse).
__attribute__((target("avx2"))) inline void storeRun4(const Points4& p, Eigen::Vector3d* q) {
  const __m256d xy02 = _mm256_shuffle_pd(p.x, p.y, 0b0000);  // x0 y0 x2 y2
  const __m256d zx13 = _mm256_shuffle_pd(p.z, p.x, 0b1010);  // z0 x1 z2 x3
  const __m256d yz13 = _mm256_shuffle_pd(p.y, p.z, 0b1111);  // y1 z1 y3 z3
  double* d = q->data();
  _mm256_storeu_pd(d, _mm256_permute2f128_pd(xy02, zx13, 0x20));
  _mm256_storeu_pd(d + 4, _mm256_permute2f128_pd(yz13, xy02, 0x30));
  _mm256_storeu_pd(d + 8, _mm256_permute2f128_pd(zx13, yz13, 0x31));
}

/// Four consecutive records of two doubles each (16 bytes: a pair of fields) from `record` on,
/// de-interleaved: the first fields of the four, and the second.
__attribute__((target("avx2"))) inline void splitPairs4(const double* record, __m256d& first,
                                                        __m256d& second) {
  const __m256d r01 = _mm256_loadu_pd(record), r23 = _mm256_loadu_pd(record + 4);
  first = _mm256_permute4x64_pd(_mm256_unpacklo_pd(r01, r23), 0xD8);
  second = _mm256_permute4x64_pd(_mm256_unpackhi_pd(r01, r23), 0xD8);
}

/// A 3-vector as a row (x, y, z, 0), and back: a running sum of vectors held in one register.
__attribute__((target("avx2"))) inline __m256d rowOf(const Eigen::Vector3d& v) {
  return _mm256_setr_pd(v.x(), v.y(), v.z(), 0.0);
}
__attribute__((target("avx2"))) inline Eigen::Vector3d vectorOf(__m256d row) {
  alignas(32) double r[4];
  _mm256_store_pd(r, row);
  return {r[0], r[1], r[2]};
}

/// sum + v's lanes 0, 1, 2, 3 in turn, as rows: each component takes its four terms in lane order (the
/// one-at-a-time sum's order).
__attribute__((target("avx2"))) inline __m256d addLaneRows(__m256d sum, const Points4& v) {
  const __m256d zero = _mm256_setzero_pd();
  const __m256d xy02 = _mm256_unpacklo_pd(v.x, v.y), xy13 = _mm256_unpackhi_pd(v.x, v.y);
  const __m256d z02 = _mm256_unpacklo_pd(v.z, zero), z13 = _mm256_unpackhi_pd(v.z, zero);
  sum = _mm256_add_pd(sum, _mm256_permute2f128_pd(xy02, z02, 0x20));
  sum = _mm256_add_pd(sum, _mm256_permute2f128_pd(xy13, z13, 0x20));
  sum = _mm256_add_pd(sum, _mm256_permute2f128_pd(xy02, z02, 0x31));
  return _mm256_add_pd(sum, _mm256_permute2f128_pd(xy13, z13, 0x31));
}

/// (a x b) lane by lane, as Eigen's cross: (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0).
__attribute__((target("avx2"))) inline Points4 cross4(const Points4& a, const Points4& b) {
  return {_mm256_sub_pd(_mm256_mul_pd(a.y, b.z), _mm256_mul_pd(a.z, b.y)),
          _mm256_sub_pd(_mm256_mul_pd(a.z, b.x), _mm256_mul_pd(a.x, b.z)),
          _mm256_sub_pd(_mm256_mul_pd(a.x, b.y), _mm256_mul_pd(a.y, b.x))};
}

/// (a . b) lane by lane, as Eigen's: (a0 b0 + a1 b1) + a2 b2.
__attribute__((target("avx2"))) inline __m256d dot4(const Points4& a, const Points4& b) {
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a.x, b.x), _mm256_mul_pd(a.y, b.y)),
                       _mm256_mul_pd(a.z, b.z));
}

/// a + b, a - b and s a, lane by lane.
__attribute__((target("avx2"))) inline Points4 plus(const Points4& a, const Points4& b) {
  return {_mm256_add_pd(a.x, b.x), _mm256_add_pd(a.y, b.y), _mm256_add_pd(a.z, b.z)};
}
__attribute__((target("avx2"))) inline Points4 minus(const Points4& a, const Points4& b) {
  return {_mm256_sub_pd(a.x, b.x), _mm256_sub_pd(a.y, b.y), _mm256_sub_pd(a.z, b.z)};
}
__attribute__((target("avx2"))) inline Points4 times(__m256d s, const Points4& a) {
  return {_mm256_mul_pd(s, a.x), _mm256_mul_pd(s, a.y), _mm256_mul_pd(s, a.z)};
}

/// A vector in every lane.
__attribute__((target("avx2"))) inline Points4 broadcast4(const Eigen::Vector3d& v) {
  return {_mm256_set1_pd(v.x()), _mm256_set1_pd(v.y()), _mm256_set1_pd(v.z())};
}

}  // namespace deform
#endif
