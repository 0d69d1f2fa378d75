// The per-frame skin pass v'_j = v_j + sum_k w_jk d_(i_jk) (Kenwright 2015, equation 1) over the layouts of
// skin_layout.cpp. The slots are read once and the displacement table (a few hundred points) stays in L1.
// Streaming (non-temporal) stores of the output were tried and did not pay here (docs/BENCHMARKS.md).
#include <deform/skin.hpp>

#include <algorithm>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define DEFORM_SKIN_AVX2 1  // an AVX2 form, chosen at run time where the machine has it
#endif

namespace deform {
namespace {

// Slot readers: index and weight (as a float: the fixed-point integer, exact in float) of slot s.
// weights4: slots s .. s + 3's weights in one register, converted together (the same values as weightAt).
template <class Index>
struct FloatSlots {
  const Index* index;
  const float* weight;
  uint32_t indexAt(std::size_t s) const { return index[s]; }
  float weightAt(std::size_t s) const { return weight[s]; }
#if defined(__SSE2__)
  __m128 weights4(std::size_t s) const {
    return _mm_loadu_ps(weight + s);
  }
#endif
};
template <class Index>
struct Unorm16Slots {
  const Index* index;
  const uint16_t* weight;
  uint32_t indexAt(std::size_t s) const { return index[s]; }
  float weightAt(std::size_t s) const { return static_cast<float>(weight[s]); }
#if defined(__SSE2__)
  __m128 weights4(std::size_t s) const {
    const __m128i q = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(weight + s));
    return _mm_cvtepi32_ps(_mm_unpacklo_epi16(q, _mm_setzero_si128()));
  }
#endif
};
struct Packed24Slots {
  const uint32_t* slot;
  uint32_t indexAt(std::size_t s) const { return slot[s] & 0xFFu; }
  float weightAt(std::size_t s) const { return static_cast<float>(static_cast<int32_t>(slot[s]) >> 8); }
#if defined(__SSE2__)
  __m128 weights4(std::size_t s) const {
    const __m128i q = _mm_loadu_si128(reinterpret_cast<const __m128i*>(slot + s));
    return _mm_cvtepi32_ps(_mm_srai_epi32(q, 8));
  }
#endif
};

// Every form sums the even and the odd influences separately and adds the two sums to the rest position:
// two short dependency chains instead of one long one, and the same order of operations in all, so the
// scalar and SSE forms give bit-identical results.

/// One vertex, scalar.
template <class Slots>
inline void deformVertexScalar(const Slots& slots, std::size_t first, std::size_t K,
                               const Eigen::Vector3f& rest, const float* d, Eigen::Vector3f& out) {
  float even[3] = {0, 0, 0}, odd[3] = {0, 0, 0};
  for (std::size_t k = 0; k < K; ++k) {
    const float* di = d + 4 * static_cast<std::size_t>(slots.indexAt(first + k));
    const float w = slots.weightAt(first + k);
    float* sum = (k % 2 == 0) ? even : odd;
    for (int a = 0; a < 3; ++a) sum[a] += w * di[a];
  }
  out = Eigen::Vector3f(rest.x() + (even[0] + odd[0]), rest.y() + (even[1] + odd[1]),
                        rest.z() + (even[2] + odd[2]));
}

#if defined(__SSE2__)
/// sum_k w_k d_(i_k) of one vertex as x, y, z, 0.
template <std::size_t KFixed, class Slots>
inline __m128 displacementSum(const Slots& slots, std::size_t first, std::size_t K_runtime, const float* d) {
  const std::size_t K = KFixed ? KFixed : K_runtime;
  __m128 even = _mm_setzero_ps(), odd = _mm_setzero_ps();
  std::size_t k = 0;
  const auto term = [&](__m128 w4, int lane, std::size_t slot) {
    const float* di = d + 4 * static_cast<std::size_t>(slots.indexAt(slot));
    const __m128 w = lane == 0   ? _mm_shuffle_ps(w4, w4, 0x00)
                     : lane == 1 ? _mm_shuffle_ps(w4, w4, 0x55)
                     : lane == 2 ? _mm_shuffle_ps(w4, w4, 0xAA)
                                 : _mm_shuffle_ps(w4, w4, 0xFF);
    return _mm_mul_ps(w, _mm_load_ps(di));
  };
  // Four slots at a time: their weights loaded and converted together.
  for (; k + 4 <= K; k += 4) {
    const __m128 w4 = slots.weights4(first + k);
    even = _mm_add_ps(even, term(w4, 0, first + k));
    odd = _mm_add_ps(odd, term(w4, 1, first + k + 1));
    even = _mm_add_ps(even, term(w4, 2, first + k + 2));
    odd = _mm_add_ps(odd, term(w4, 3, first + k + 3));
  }
  for (; k + 1 < K; k += 2) {
    const float* d0 = d + 4 * static_cast<std::size_t>(slots.indexAt(first + k));
    const float* d1 = d + 4 * static_cast<std::size_t>(slots.indexAt(first + k + 1));
    even = _mm_add_ps(even, _mm_mul_ps(_mm_set1_ps(slots.weightAt(first + k)), _mm_load_ps(d0)));
    odd = _mm_add_ps(odd, _mm_mul_ps(_mm_set1_ps(slots.weightAt(first + k + 1)), _mm_load_ps(d1)));
  }
  if (k < K) {
    const float* d0 = d + 4 * static_cast<std::size_t>(slots.indexAt(first + k));
    even = _mm_add_ps(even, _mm_mul_ps(_mm_set1_ps(slots.weightAt(first + k)), _mm_load_ps(d0)));
  }
  return _mm_add_ps(even, odd);
}
#endif

#if defined(DEFORM_SKIN_AVX2)
/// Whether the machine runs AVX2 (asked once).
bool hasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

/// deformRangeImpl for K a multiple of four, two slots per 256-bit register: the low half sums the even
/// slots and the high half the odd ones, each in the order the SSE form sums them, with no fused
/// multiply-add (the target is AVX2 alone), so the results are the SSE form's to the bit.
template <std::size_t KFixed, class Slots>
__attribute__((target("avx2"))) void deformRangeAvx2(const Slots& slots, const Eigen::Vector3f* rest,
                                                     const float* d, Eigen::Vector3f* out, std::size_t begin,
                                                     std::size_t end) {
  static_assert(KFixed > 0 && KFixed % 4 == 0, "four slots at a time");
  const __m256i first_pair = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
  const __m256i second_pair = _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3);
  std::size_t j = begin;
  for (; j + 1 < end; ++j) {  // the last vertex in scalar form, as the SSE form does
    const std::size_t first = j * KFixed;
    __m256 sum = _mm256_setzero_ps();
    for (std::size_t k = 0; k < KFixed; k += 4) {
      const __m256 w = _mm256_castps128_ps256(slots.weights4(first + k));
      __m256 d01 = _mm256_castps128_ps256(_mm_load_ps(d + 4 * std::size_t{slots.indexAt(first + k)}));
      d01 = _mm256_insertf128_ps(d01, _mm_load_ps(d + 4 * std::size_t{slots.indexAt(first + k + 1)}), 1);
      __m256 d23 = _mm256_castps128_ps256(_mm_load_ps(d + 4 * std::size_t{slots.indexAt(first + k + 2)}));
      d23 = _mm256_insertf128_ps(d23, _mm_load_ps(d + 4 * std::size_t{slots.indexAt(first + k + 3)}), 1);
      sum = _mm256_add_ps(sum, _mm256_mul_ps(_mm256_permutevar8x32_ps(w, first_pair), d01));
      sum = _mm256_add_ps(sum, _mm256_mul_ps(_mm256_permutevar8x32_ps(w, second_pair), d23));
    }
    const __m128 total = _mm_add_ps(_mm256_castps256_ps128(sum), _mm256_extractf128_ps(sum, 1));
    _mm_storeu_ps(out[j].data(), _mm_add_ps(_mm_loadu_ps(rest[j].data()), total));
  }
  for (; j < end; ++j) deformVertexScalar(slots, j * KFixed, KFixed, rest[j], d, out[j]);
}
#endif

template <std::size_t KFixed, class Slots>
void deformRangeImpl(const Slots& slots, std::size_t K_runtime, const Eigen::Vector3f* rest, const float* d,
                     Eigen::Vector3f* out, std::size_t begin, std::size_t end) {
  const std::size_t K = KFixed ? KFixed : K_runtime;
#if defined(DEFORM_SKIN_AVX2)
  if constexpr (KFixed > 0 && KFixed % 4 == 0)
    if (hasAvx2()) return deformRangeAvx2<KFixed>(slots, rest, d, out, begin, end);
#endif
  std::size_t j = begin;
#if defined(__SSE2__)
  // 16-byte stores of a 12-byte vertex touch the next vertex's x: the last vertex of the range is done in
  // scalar form so a neighbouring range (another thread) is never written.
  for (; j + 1 < end; ++j)
    _mm_storeu_ps(out[j].data(),
                  _mm_add_ps(_mm_loadu_ps(rest[j].data()), displacementSum<KFixed>(slots, j * K, K, d)));
#endif
  for (; j < end; ++j) deformVertexScalar(slots, j * K, K, rest[j], d, out[j]);
}

template <class Slots>
void dispatchK(const Slots& slots, std::size_t K, const Eigen::Vector3f* rest, const float* d,
               Eigen::Vector3f* out, std::size_t begin, std::size_t end) {
  if (begin >= end) return;
  switch (K) {
    case 4:
      return deformRangeImpl<4>(slots, K, rest, d, out, begin, end);
    case 8:
      return deformRangeImpl<8>(slots, K, rest, d, out, begin, end);
    case 16:
      return deformRangeImpl<16>(slots, K, rest, d, out, begin, end);
    default:
      return deformRangeImpl<0>(slots, K, rest, d, out, begin, end);
  }
}

/// The spline's lattice pass (skin_lattice.hpp): vertex j's 27 nodes are base_j + a + b stride_y +
/// c stride_z (a, b, c in 0..2) of weight wx[a] wy[b] wz[c], from 9 unorm16 axis weights. 22 bytes a vertex
/// instead of 27 slots; each sum in one order: along x first, then y, then z.
template <bool kVector>
inline void deformSeparableVertex(const uint32_t base, const uint16_t* w, const uint32_t stride_y,
                                  const uint32_t stride_z, const Eigen::Vector3f& rest, const float* d,
                                  Eigen::Vector3f& out) {
  constexpr float kInverse = 1.0f / 65535.0f;
  const float wx[3] = {w[0] * kInverse, w[1] * kInverse, w[2] * kInverse};
  const float wy[3] = {w[3] * kInverse, w[4] * kInverse, w[5] * kInverse};
  const float wz[3] = {w[6] * kInverse, w[7] * kInverse, w[8] * kInverse};
#if defined(__SSE2__)
  if constexpr (kVector) {
    __m128 sum = _mm_setzero_ps();
    for (uint32_t c = 0; c < 3; ++c)
      for (uint32_t b = 0; b < 3; ++b) {
        const float* row = d + 4 * std::size_t{base + b * stride_y + c * stride_z};
        __m128 t = _mm_mul_ps(_mm_set1_ps(wx[0]), _mm_load_ps(row));
        t = _mm_add_ps(t, _mm_mul_ps(_mm_set1_ps(wx[1]), _mm_load_ps(row + 4)));
        t = _mm_add_ps(t, _mm_mul_ps(_mm_set1_ps(wx[2]), _mm_load_ps(row + 8)));
        sum = _mm_add_ps(sum, _mm_mul_ps(_mm_set1_ps(wy[b] * wz[c]), t));
      }
    _mm_storeu_ps(out.data(), _mm_add_ps(_mm_loadu_ps(rest.data()), sum));
    return;
  }
#endif
  float sum[3] = {0, 0, 0};
  for (uint32_t c = 0; c < 3; ++c)
    for (uint32_t b = 0; b < 3; ++b) {
      const float* row = d + 4 * std::size_t{base + b * stride_y + c * stride_z};
      const float wyz = wy[b] * wz[c];
      for (int a = 0; a < 3; ++a) {
        float t = wx[0] * row[a];
        t = t + wx[1] * row[4 + a];
        t = t + wx[2] * row[8 + a];
        sum[a] = sum[a] + wyz * t;
      }
    }
  out = Eigen::Vector3f(rest.x() + sum[0], rest.y() + sum[1], rest.z() + sum[2]);
}

/// d_i / scale as x, y, z, 0 floats: one aligned 16-byte load per influence, and the fixed-point weight's
/// scale folded in (rounded once, in double, to float).
std::vector<float, Eigen::aligned_allocator<float>> scaledTable(const Eigen::Vector3d* displacement_m,
                                                                std::size_t count, int64_t scale) {
  std::vector<float, Eigen::aligned_allocator<float>> table(4 * count, 0.0f);
  const double inverse = 1.0 / static_cast<double>(scale);
  for (std::size_t i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a)
      table[4 * i + static_cast<std::size_t>(a)] = static_cast<float>(displacement_m[i][a] * inverse);
  return table;
}

}  // namespace

void Skin::deformRange(const Eigen::Vector3f* rest_m, const float* scaled_xyz0, Eigen::Vector3f* out_m,
                       std::size_t begin, std::size_t end) const {
  const std::size_t K = influences_;
  switch (weight_format_) {
    case WeightFormat::separable: {
      // 16-byte stores of a 12-byte vertex touch the next vertex's x: the range's last vertex in scalar
      // form, as the other passes do (the same arithmetic, so the same bits).
      std::size_t j = begin;
      for (; j + 1 < end; ++j)
        deformSeparableVertex<true>(lattice_base_[j], &lattice_weights_[9 * j], lattice_stride_[1],
                                    lattice_stride_[2], rest_m[j], scaled_xyz0, out_m[j]);
      for (; j < end; ++j)
        deformSeparableVertex<false>(lattice_base_[j], &lattice_weights_[9 * j], lattice_stride_[1],
                                     lattice_stride_[2], rest_m[j], scaled_xyz0, out_m[j]);
      return;
    }
    case WeightFormat::packed24:
      return dispatchK(Packed24Slots{packed_.data()}, K, rest_m, scaled_xyz0, out_m, begin, end);
    case WeightFormat::unorm16:
      if (index_bytes_ == 1)
        return dispatchK(Unorm16Slots<uint8_t>{indices8_.data(), weights16_.data()}, K, rest_m, scaled_xyz0,
                         out_m, begin, end);
      if (index_bytes_ == 2)
        return dispatchK(Unorm16Slots<uint16_t>{indices16_.data(), weights16_.data()}, K, rest_m, scaled_xyz0,
                         out_m, begin, end);
      return dispatchK(Unorm16Slots<uint32_t>{indices32_.data(), weights16_.data()}, K, rest_m, scaled_xyz0,
                       out_m, begin, end);
    case WeightFormat::float32:
      if (index_bytes_ == 2)
        return dispatchK(FloatSlots<uint16_t>{indices16_.data(), weights_.data()}, K, rest_m, scaled_xyz0,
                         out_m, begin, end);
      return dispatchK(FloatSlots<uint32_t>{indices32_.data(), weights_.data()}, K, rest_m, scaled_xyz0,
                       out_m, begin, end);
  }
}

std::vector<float, Eigen::aligned_allocator<float>> Skin::slotTable(const Eigen::Vector3d* displacement_m,
                                                                    unsigned threads) const {
  if (node_count_ == 0) return scaledTable(displacement_m, control_count_, weight_scale_);
  // The spline at the lattice's nodes: point by point, each adding its weight on every node times its
  // displacement (a loop over nodes the compiler vectorises), so every node sums its points in index order
  // whatever the threads split: the same bits on any thread count.
  // In metres: the separable pass turns its weights to fractions itself (deformSeparableVertex).
  std::vector<float, Eigen::aligned_allocator<float>> table(4 * node_count_, 0.0f);
  parallelFor(node_count_, threads, [&](std::size_t begin, std::size_t end) {
    std::vector<float> x(end - begin, 0.0f), y(end - begin, 0.0f), z(end - begin, 0.0f);
    for (std::size_t i = 0; i < control_count_; ++i) {
      const float* w = &node_from_control_[i * node_count_ + begin];
      const Eigen::Vector3f d = displacement_m[i].cast<float>();
      for (std::size_t n = 0; n < end - begin; ++n) {
        x[n] += w[n] * d.x();
        y[n] += w[n] * d.y();
        z[n] += w[n] * d.z();
      }
    }
    for (std::size_t n = 0; n < end - begin; ++n) {
      float* t = &table[4 * (begin + n)];
      t[0] = x[n];
      t[1] = y[n];
      t[2] = z[n];
    }
  });
  return table;
}

void Skin::deform(const Eigen::Vector3f* rest_m, const Eigen::Vector3d* displacement_m,
                  Eigen::Vector3f* out_m, unsigned threads) const {
  const auto table = slotTable(displacement_m, threads);
  parallelFor(vertex_count_, threads, [&](std::size_t begin, std::size_t end) {
    deformRange(rest_m, table.data(), out_m, begin, end);
  });
}

std::size_t Skin::deformMoved(const Eigen::Vector3f* rest_m, const Eigen::Vector3d* displacement_m,
                              const std::vector<uint8_t>& moved, Eigen::Vector3f* out_m, unsigned threads,
                              std::vector<uint8_t>* recomputed_flags) const {
  std::vector<uint8_t> local;
  std::vector<uint8_t>& dirty = recomputed_flags ? *recomputed_flags : local;
  dirty.assign(vertex_count_, 0);
  if (node_count_ > 0) {  // the spline: a point that moves moves every node, so every vertex
    const auto flags_end =
        moved.begin() + static_cast<std::ptrdiff_t>(std::min(moved.size(), control_count_));
    if (std::none_of(moved.begin(), flags_end, [](uint8_t flag) { return flag != 0; })) return 0;
    deform(rest_m, displacement_m, out_m, threads);
    dirty.assign(vertex_count_, 1);
    return vertex_count_;
  }
  std::size_t influenced = 0;
  for (std::size_t i = 0; i < control_count_ && i < moved.size(); ++i) {
    if (!moved[i]) continue;
    for (std::size_t s = influenced_begin_[i]; s < influenced_begin_[i + 1]; ++s)
      dirty[influenced_vertices_[s]] = 1;
    influenced += influenced_begin_[i + 1] - influenced_begin_[i];
  }
  if (influenced == 0) return 0;
  const auto table = slotTable(displacement_m, threads);
  std::size_t recomputed = 0;
  for (uint8_t flag : dirty) recomputed += flag;
  parallelFor(vertex_count_, threads, [&](std::size_t begin, std::size_t end) {
    // Runs of dirty vertices go through the same pass as a full deform, so the results are identical.
    std::size_t j = begin;
    while (j < end) {
      while (j < end && !dirty[j]) ++j;
      std::size_t run_end = j;
      while (run_end < end && dirty[run_end]) ++run_end;
      if (j < run_end) deformRange(rest_m, table.data(), out_m, j, run_end);
      j = run_end;
    }
  });
  return recomputed;
}

}  // namespace deform
