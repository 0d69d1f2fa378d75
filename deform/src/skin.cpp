// Building the embedding weights (skin_weights.cpp) and the per-frame deform pass.
#include <deform/error.hpp>
#include <deform/skin.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include <string>

#include "nearest_points.hpp"
#include "skin_weights.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace deform {
const char* skinMethodName(SkinMethod method) {
  return method == SkinMethod::mls ? "mls" : "idw";
}

bool parseSkinMethod(const std::string& name, SkinMethod& method) {
  if (name == "idw")
    method = SkinMethod::idw;
  else if (name == "mls")
    method = SkinMethod::mls;
  else
    return false;
  return true;
}

Skin Skin::build(const std::vector<Eigen::Vector3f>& vertices_m,
                 const std::vector<Eigen::Vector3d>& control_rest_m, const SkinOptions& options) {
  if (!(options.alpha > 0 && options.alpha <= 64))
    throw InputError("alpha must be in (0, 64] (got " + std::to_string(options.alpha) + ")");
  if (control_rest_m.empty()) throw InputError("skin: no control points");
  for (const auto& c : control_rest_m)
    if (!c.allFinite()) throw InputError("skin: a control point has a non-finite coordinate");
  for (const auto& v : vertices_m)
    if (!v.allFinite()) throw InputError("skin: a vertex has a non-finite coordinate");

  Skin skin;
  const std::size_t n = control_rest_m.size();
  skin.vertex_count_ = vertices_m.size();
  skin.control_count_ = n;
  skin.alpha_ = options.alpha;
  skin.method_ = options.method;
  skin.influences_ = options.k_nearest == 0 ? n : std::min(options.k_nearest, n);
  skin.wide_indices_ = n > 65536;
  const std::size_t slots = skin.vertex_count_ * skin.influences_;
  (skin.wide_indices_ ? skin.indices32_.resize(slots) : skin.indices16_.resize(slots));
  skin.weights_.resize(slots);

  const std::size_t K = skin.influences_;
  // Below a few dozen points, or dense, a scan of every point is as fast as a tree.
  const bool use_tree = K < n && n > 32;
  std::optional<detail::PointKdTree> tree;
  if (use_tree) tree.emplace(control_rest_m);
  parallelFor(skin.vertex_count_, options.threads, [&](std::size_t begin, std::size_t end) {
    std::vector<detail::RankedPoint> ranked, candidates;
    std::vector<double> distance(K), weight(K);
    std::vector<Eigen::Vector3d> point(K);
    std::vector<uint32_t> chosen(K);
    for (std::size_t j = begin; j < end; ++j) {
      const Eigen::Vector3d v = vertices_m[j].cast<double>();
      if (use_tree) {
        tree->nearest(v, K, ranked);
      } else {
        ranked.clear();
        for (uint32_t i = 0; i < n; ++i) ranked.push_back({(control_rest_m[i] - v).squaredNorm(), i});
        if (K < n)
          std::nth_element(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(K - 1), ranked.end());
        ranked.resize(K);
      }
      // Affine MLS over points in a plane cannot follow a vertex off it: look further for one that can,
      // among the nearest few dozen, then (a large flat side of the hull) among all.
      if (options.method == SkinMethod::mls && K < n && detail::offsetOutOfSpan(v, control_rest_m, ranked)) {
        const std::vector<detail::RankedPoint> nearest = ranked;
        bool widened = false;
        if (use_tree) {
          tree->nearest(v, std::min(n, 4 * K + 16), candidates);
          widened = detail::widenSpan(v, control_rest_m, ranked, candidates);
        }
        if (!widened) {
          ranked = nearest;
          candidates.clear();
          for (uint32_t i = 0; i < n; ++i) candidates.push_back({(control_rest_m[i] - v).squaredNorm(), i});
          std::sort(candidates.begin(), candidates.end());
          detail::widenSpan(v, control_rest_m, ranked, candidates);
        }
      }
      // Slots in index order: deterministic, and the displacement reads walk forward through memory.
      std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
      for (std::size_t k = 0; k < K; ++k) {
        chosen[k] = ranked[k].index;
        distance[k] = std::sqrt(ranked[k].distance2_m2);
        point[k] = control_rest_m[chosen[k]];
      }
      if (options.method == SkinMethod::mls)
        detail::movingLeastSquaresWeights(v, point.data(), distance.data(), K, options.alpha, weight.data());
      else
        detail::inverseDistanceWeights(distance.data(), K, options.alpha, weight.data());
      for (std::size_t k = 0; k < K; ++k) {
        const std::size_t s = j * K + k;
        if (skin.wide_indices_)
          skin.indices32_[s] = chosen[k];
        else
          skin.indices16_[s] = static_cast<uint16_t>(chosen[k]);
        skin.weights_[s] = static_cast<float>(weight[k]);
      }
    }
  });
  // Reverse index (counting sort by control point); slots with zero weight influence nothing.
  skin.influenced_begin_.assign(n + 1, 0);
  for (std::size_t j = 0; j < skin.vertex_count_; ++j)
    for (std::size_t k = 0; k < K; ++k)
      if (skin.slotWeight(j, k) != 0.0f) ++skin.influenced_begin_[skin.slotIndex(j, k) + 1];
  for (std::size_t i = 0; i < n; ++i) skin.influenced_begin_[i + 1] += skin.influenced_begin_[i];
  skin.influenced_vertices_.resize(skin.influenced_begin_[n]);
  std::vector<std::size_t> fill(skin.influenced_begin_.begin(), skin.influenced_begin_.end() - 1);
  for (std::size_t j = 0; j < skin.vertex_count_; ++j)
    for (std::size_t k = 0; k < K; ++k)
      if (skin.slotWeight(j, k) != 0.0f)
        skin.influenced_vertices_[fill[skin.slotIndex(j, k)]++] = static_cast<uint32_t>(j);
  return skin;
}

float Skin::weight(std::size_t j, uint32_t i) const {
  for (std::size_t k = 0; k < influences_; ++k)
    if (slotIndex(j, k) == i) return slotWeight(j, k);
  return 0.0f;
}

std::size_t Skin::memoryBytes() const {
  return weights_.size() * sizeof(float) + indices16_.size() * sizeof(uint16_t) +
         indices32_.size() * sizeof(uint32_t);
}

std::size_t Skin::bytesPerVertex() const {
  const std::size_t index_bytes = wide_indices_ ? 4 : 2;
  return 2 * sizeof(Eigen::Vector3f) + influences_ * (index_bytes + sizeof(float));
}

void Skin::deform(const Eigen::Vector3f* rest_m, const Eigen::Vector3d* displacement_m,
                  Eigen::Vector3f* out_m, unsigned threads) const {
  // Displacements as x, y, z, 0 floats: one aligned 16-byte load per influence, and the whole table of a
  // few hundred control points stays in L1.
  std::vector<float> packed(4 * control_count_);
  for (std::size_t i = 0; i < control_count_; ++i) {
    packed[4 * i + 0] = static_cast<float>(displacement_m[i].x());
    packed[4 * i + 1] = static_cast<float>(displacement_m[i].y());
    packed[4 * i + 2] = static_cast<float>(displacement_m[i].z());
    packed[4 * i + 3] = 0.0f;
  }
  parallelFor(vertex_count_, threads, [&](std::size_t begin, std::size_t end) {
    deformRange(rest_m, packed.data(), out_m, begin, end);
  });
}

std::size_t Skin::deformMoved(const Eigen::Vector3f* rest_m, const Eigen::Vector3d* displacement_m,
                              const std::vector<uint8_t>& moved, Eigen::Vector3f* out_m, unsigned threads,
                              std::vector<uint8_t>* recomputed_flags) const {
  std::vector<uint8_t> local;
  std::vector<uint8_t>& dirty = recomputed_flags ? *recomputed_flags : local;
  dirty.assign(vertex_count_, 0);
  std::size_t influenced = 0;
  for (std::size_t i = 0; i < control_count_ && i < moved.size(); ++i) {
    if (!moved[i]) continue;
    for (std::size_t s = influenced_begin_[i]; s < influenced_begin_[i + 1]; ++s)
      dirty[influenced_vertices_[s]] = 1;
    influenced += influenced_begin_[i + 1] - influenced_begin_[i];
  }
  if (influenced == 0) return 0;
  std::vector<float> packed(4 * control_count_);
  for (std::size_t i = 0; i < control_count_; ++i)
    for (int a = 0; a < 3; ++a)
      packed[4 * i + static_cast<std::size_t>(a)] = static_cast<float>(displacement_m[i][a]);
  std::size_t recomputed = 0;
  for (uint8_t d : dirty) recomputed += d;
  parallelFor(vertex_count_, threads, [&](std::size_t begin, std::size_t end) {
    // Runs of dirty vertices go through the same pass as a full deform, so the results are identical.
    std::size_t j = begin;
    while (j < end) {
      while (j < end && !dirty[j]) ++j;
      std::size_t run_end = j;
      while (run_end < end && dirty[run_end]) ++run_end;
      if (j < run_end) deformRange(rest_m, packed.data(), out_m, j, run_end);
      j = run_end;
    }
  });
  return recomputed;
}

namespace {

// Both forms sum the even and the odd influences separately and add the two sums to the rest position:
// two short dependency chains instead of one long one, and the same order of operations in both, so the
// scalar and the SSE forms give bit-identical results.

/// One vertex, scalar: v'_j = v_j + sum_k w_jk d_(i_jk).
template <class Index>
inline void deformVertexScalar(const Eigen::Vector3f& rest, const Index* idx, const float* w, std::size_t K,
                               const float* d, Eigen::Vector3f& out) {
  float even[3] = {0, 0, 0}, odd[3] = {0, 0, 0};
  for (std::size_t k = 0; k < K; ++k) {
    const float* di = d + 4 * static_cast<std::size_t>(idx[k]);
    float* sum = (k % 2 == 0) ? even : odd;
    for (int a = 0; a < 3; ++a) sum[a] += w[k] * di[a];
  }
  out = Eigen::Vector3f(rest.x() + (even[0] + odd[0]), rest.y() + (even[1] + odd[1]),
                        rest.z() + (even[2] + odd[2]));
}

template <std::size_t KFixed, class Index>
void deformRangeImpl(const Eigen::Vector3f* rest, const Index* indices, const float* weights,
                     std::size_t K_runtime, const float* d, Eigen::Vector3f* out, std::size_t begin,
                     std::size_t end) {
  const std::size_t K = KFixed ? KFixed : K_runtime;
  if (begin >= end) return;
  std::size_t j = begin;
#if defined(__SSE2__)
  // 16-byte loads and stores of a 12-byte vertex touch the next vertex's x: the last vertex of the range
  // is done in scalar form so a neighbouring range (another thread) is never written.
  for (; j + 1 < end; ++j) {
    const Index* idx = indices + j * K;
    const float* w = weights + j * K;
    __m128 even = _mm_setzero_ps(), odd = _mm_setzero_ps();
    std::size_t k = 0;
    for (; k + 1 < K; k += 2) {
      even = _mm_add_ps(even,
                        _mm_mul_ps(_mm_set1_ps(w[k]), _mm_load_ps(d + 4 * static_cast<std::size_t>(idx[k]))));
      odd = _mm_add_ps(
          odd, _mm_mul_ps(_mm_set1_ps(w[k + 1]), _mm_load_ps(d + 4 * static_cast<std::size_t>(idx[k + 1]))));
    }
    if (k < K)
      even = _mm_add_ps(even,
                        _mm_mul_ps(_mm_set1_ps(w[k]), _mm_load_ps(d + 4 * static_cast<std::size_t>(idx[k]))));
    _mm_storeu_ps(out[j].data(), _mm_add_ps(_mm_loadu_ps(rest[j].data()), _mm_add_ps(even, odd)));
  }
#endif
  for (; j < end; ++j) deformVertexScalar(rest[j], indices + j * K, weights + j * K, K, d, out[j]);
}

template <class Index>
void dispatchK(const Eigen::Vector3f* rest, const Index* indices, const float* weights, std::size_t K,
               const float* d, Eigen::Vector3f* out, std::size_t begin, std::size_t end) {
  switch (K) {
    case 4:
      return deformRangeImpl<4>(rest, indices, weights, K, d, out, begin, end);
    case 8:
      return deformRangeImpl<8>(rest, indices, weights, K, d, out, begin, end);
    case 16:
      return deformRangeImpl<16>(rest, indices, weights, K, d, out, begin, end);
    default:
      return deformRangeImpl<0>(rest, indices, weights, K, d, out, begin, end);
  }
}

}  // namespace

void Skin::deformRange(const Eigen::Vector3f* rest_m, const float* displacement_xyz0_m,
                       Eigen::Vector3f* out_m, std::size_t begin, std::size_t end) const {
  if (wide_indices_)
    dispatchK(rest_m, indices32_.data(), weights_.data(), influences_, displacement_xyz0_m, out_m, begin,
              end);
  else
    dispatchK(rest_m, indices16_.data(), weights_.data(), influences_, displacement_xyz0_m, out_m, begin,
              end);
}

}  // namespace deform
