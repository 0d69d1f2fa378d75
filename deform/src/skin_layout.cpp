// How a skin's weights are stored (deform/skin.hpp, SkinLayout): the per-frame pass is memory-bound, so
// each byte a slot sheds is time saved (docs/BENCHMARKS.md, issue 13). The fixed-point forms round each
// vertex's weights so that their integers sum exactly to the scale: a translation of every control point
// still moves the vertex by exactly that translation's scaled sum, and partition of unity holds exactly.
#include <deform/skin.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace deform {
namespace {

/// Rounds w_k x scale to integers q_k with sum_k q_k == scale exactly and |q_k - w_k scale| < 1 for
/// well-normalised weights: floor each, then hand the missing units to the largest remainders (Hamilton's
/// largest-remainder method). `lowest`/`highest` bound each q_k (a unit is never given past them).
void roundToExactSum(const float* w, std::size_t K, int64_t scale, int64_t lowest, int64_t highest,
                     int64_t* q, std::vector<std::size_t>& order, std::vector<double>& remainder) {
  int64_t sum = 0;
  remainder.resize(K);
  for (std::size_t k = 0; k < K; ++k) {
    const double exact = static_cast<double>(w[k]) * static_cast<double>(scale);
    q[k] = std::clamp(static_cast<int64_t>(std::floor(exact)), lowest, highest);
    remainder[k] = exact - static_cast<double>(q[k]);
    sum += q[k];
  }
  int64_t missing = scale - sum;
  order.resize(K);
  std::iota(order.begin(), order.end(), std::size_t{0});
  // Largest remainder first; ties by slot, so the rounding is deterministic.
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return remainder[a] > remainder[b]; });
  for (std::size_t pass = 0; missing != 0 && pass < 4; ++pass) {
    bool changed = false;
    for (std::size_t r = 0; r < K && missing != 0; ++r) {
      // Add to the largest remainders, take from the smallest.
      const std::size_t k = missing > 0 ? order[r] : order[K - 1 - r];
      const int64_t step = missing > 0 ? 1 : -1;
      if (q[k] + step < lowest || q[k] + step > highest) continue;
      q[k] += step;
      missing -= step;
      changed = true;
    }
    if (!changed) break;
  }
}

}  // namespace

void Skin::storeCompact(const std::vector<float>& weights, const std::vector<uint32_t>& indices) {
  const std::size_t K = influences_, slots = weights.size();
  const bool narrow = control_count_ <= 256, wide = control_count_ > 65536;
  weight_format_ = WeightFormat::float32;
  weight_scale_ = 1;
  if (layout_ == SkinLayout::compact && method_ == SkinMethod::idw) {
    weight_format_ = WeightFormat::unorm16;  // idw weights lie in [0, 1]
    weight_scale_ = 65535;
  } else if (layout_ == SkinLayout::compact && narrow) {
    // mls: signed weights, 24 bits; the scale a power of two that keeps the largest weight in range, at
    // most 2^21 (a step of 4.8e-7: the affine reproduction stays under 1e-6 m on a car, tested).
    float largest = 0;
    for (float w : weights) largest = std::max(largest, std::abs(w));
    // Room for the largest weight and the K units the exact-sum rounding may add.
    const auto fits = [&](int64_t scale) {
      return static_cast<double>(largest) * static_cast<double>(scale) + static_cast<double>(K) < 8388607.0;
    };
    int64_t scale = int64_t{1} << 21;
    while (scale > (int64_t{1} << 14) && !fits(scale)) scale /= 2;
    if (fits(scale)) {
      weight_format_ = WeightFormat::packed24;
      weight_scale_ = scale;
    }
  }
  index_bytes_ =
      weight_format_ == WeightFormat::packed24 || (weight_format_ == WeightFormat::unorm16 && narrow)
          ? 1
          : (wide ? 4 : 2);
  if (weight_format_ == WeightFormat::float32) weights_ = weights;
  if (weight_format_ != WeightFormat::packed24) {
    if (index_bytes_ == 1) indices8_.assign(indices.begin(), indices.end());
    if (index_bytes_ == 2) indices16_.assign(indices.begin(), indices.end());
    if (index_bytes_ == 4) indices32_ = indices;
  }
  if (weight_format_ == WeightFormat::float32) return;
  (weight_format_ == WeightFormat::unorm16 ? weights16_.resize(slots) : packed_.resize(slots));
  const int64_t lowest = weight_format_ == WeightFormat::unorm16 ? 0 : -8388608;
  const int64_t highest = weight_format_ == WeightFormat::unorm16 ? 65535 : 8388607;
  std::vector<int64_t> q(K);
  std::vector<std::size_t> order;
  std::vector<double> remainder;
  for (std::size_t j = 0; j < vertex_count_; ++j) {
    roundToExactSum(&weights[j * K], K, weight_scale_, lowest, highest, q.data(), order, remainder);
    for (std::size_t k = 0; k < K; ++k) {
      const std::size_t s = j * K + k;
      if (weight_format_ == WeightFormat::unorm16)
        weights16_[s] = static_cast<uint16_t>(q[k]);
      else  // the signed weight in the high 24 bits, the index in the low 8
        packed_[s] = (static_cast<uint32_t>(q[k]) << 8) | (indices[s] & 0xFFu);
    }
  }
}

void Skin::storeSeparable(const std::vector<uint32_t>& base, const std::vector<float>& axis_weights,
                          const uint32_t stride[3]) {
  weight_format_ = WeightFormat::separable;
  constexpr int64_t kAxisScale = 65535;
  weight_scale_ = kAxisScale * kAxisScale * kAxisScale;  // a slot's weight: the product of three
  index_bytes_ = 4;
  lattice_base_ = base;
  for (int a = 0; a < 3; ++a) lattice_stride_[a] = stride[a];
  lattice_weights_.resize(axis_weights.size());
  int64_t q[3];
  std::vector<std::size_t> order;
  std::vector<double> remainder;
  for (std::size_t g = 0; g < axis_weights.size(); g += 3) {
    // Each axis's three sum exactly to the scale, so the 27 products sum exactly to the scale cubed.
    roundToExactSum(&axis_weights[g], 3, kAxisScale, 0, kAxisScale, q, order, remainder);
    for (std::size_t k = 0; k < 3; ++k) lattice_weights_[g + k] = static_cast<uint16_t>(q[k]);
  }
}

uint32_t Skin::slotIndex(std::size_t j, std::size_t k) const {
  if (weight_format_ == WeightFormat::separable)
    return lattice_base_[j] + static_cast<uint32_t>(k % 3) * lattice_stride_[0] +
           static_cast<uint32_t>(k / 3 % 3) * lattice_stride_[1] +
           static_cast<uint32_t>(k / 9) * lattice_stride_[2];
  const std::size_t s = j * influences_ + k;
  if (weight_format_ == WeightFormat::packed24) return packed_[s] & 0xFFu;
  return index_bytes_ == 1 ? indices8_[s] : index_bytes_ == 2 ? indices16_[s] : indices32_[s];
}

int64_t Skin::slotWeightFixed(std::size_t j, std::size_t k) const {
  if (weight_format_ == WeightFormat::separable) {
    const uint16_t* w = &lattice_weights_[9 * j];
    return int64_t{w[k % 3]} * int64_t{w[3 + k / 3 % 3]} * int64_t{w[6 + k / 9]};
  }
  const std::size_t s = j * influences_ + k;
  if (weight_format_ == WeightFormat::unorm16) return weights16_[s];
  if (weight_format_ == WeightFormat::packed24)
    return static_cast<int32_t>(packed_[s]) >> 8;  // C++20: arithmetic
  return 0;
}

float Skin::slotWeight(std::size_t j, std::size_t k) const {
  if (weight_format_ == WeightFormat::float32) return weights_[j * influences_ + k];
  return static_cast<float>(static_cast<double>(slotWeightFixed(j, k)) / static_cast<double>(weight_scale_));
}

std::size_t Skin::memoryBytes() const {
  return node_from_control_.size() * sizeof(float) + lattice_base_.size() * sizeof(uint32_t) +
         lattice_weights_.size() * sizeof(uint16_t) + weights_.size() * sizeof(float) +
         weights16_.size() * sizeof(uint16_t) + packed_.size() * sizeof(uint32_t) + indices8_.size() +
         indices16_.size() * sizeof(uint16_t) + indices32_.size() * sizeof(uint32_t);
}

std::size_t Skin::reverseIndexBytes() const {
  return influenced_begin_.size() * sizeof(std::size_t) + influenced_vertices_.size() * sizeof(uint32_t);
}

std::size_t Skin::bytesPerVertex() const {
  // The spline: its first node and 9 axis weights.
  if (weight_format_ == WeightFormat::separable) return 2 * sizeof(Eigen::Vector3f) + sizeof(uint32_t) + 18;
  const std::size_t slot_bytes = weight_format_ == WeightFormat::packed24  ? 4
                                 : weight_format_ == WeightFormat::unorm16 ? index_bytes_ + 2
                                                                           : index_bytes_ + 4;
  return 2 * sizeof(Eigen::Vector3f) + influences_ * slot_bytes;
}

}  // namespace deform
