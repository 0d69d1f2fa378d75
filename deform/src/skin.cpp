// Building the embedding weights (skin_weights.cpp); their storage is in skin_layout.cpp, the per-frame
// pass in skin_pass.cpp.
#include <deform/error.hpp>
#include <deform/skin.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include <string>

#include "nearest_points.hpp"
#include "skin_lattice.hpp"
#include "skin_spline.hpp"
#include "skin_weights.hpp"

namespace deform {
const char* skinMethodName(SkinMethod method) {
  return method == SkinMethod::mls ? "mls" : method == SkinMethod::spline ? "spline" : "idw";
}

SkinMethod preferredSkinMethod(std::size_t control_points, std::size_t k_nearest) {
  const bool enough_nearest = k_nearest == 0 || k_nearest >= kMlsFromNearest;
  return control_points <= kMlsUpToControlPoints && enough_nearest ? SkinMethod::mls : SkinMethod::idw;
}

bool parseSkinMethod(const std::string& name, SkinMethod& method) {
  if (name == "idw")
    method = SkinMethod::idw;
  else if (name == "mls")
    method = SkinMethod::mls;
  else if (name == "spline")
    method = SkinMethod::spline;
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

  const std::size_t n = control_rest_m.size();
  if (options.method == SkinMethod::spline && n > kSplineMostControlPoints)
    throw InputError(
        "skin: spline through every control point (a dense system, evaluated at every lattice "
        "node each frame): at most " +
        std::to_string(kSplineMostControlPoints) + " control points (got " + std::to_string(n) +
        "); idw or mls take any number");
  Skin skin;
  skin.vertex_count_ = vertices_m.size();
  skin.control_count_ = n;
  skin.alpha_ = options.alpha;
  skin.method_ = options.method;
  skin.influences_ = options.method == SkinMethod::spline ? detail::kLatticeSlots
                     : options.k_nearest == 0             ? n
                                                          : std::min(options.k_nearest, n);
  skin.layout_ = options.layout;
  if (options.method == SkinMethod::spline) {
    // The spline at the lattice's nodes (dense, N per node), the vertices on the nodes (27 each).
    const detail::SplineWeights spline(control_rest_m);
    const detail::BsplineLattice lattice = detail::bsplineLattice(vertices_m);
    skin.node_count_ = lattice.nodes_m.size();
    skin.node_from_control_.resize(skin.node_count_ * n);
    parallelFor(skin.node_count_, options.threads, [&](std::size_t begin, std::size_t end) {
      std::vector<double> row(n);
      for (std::size_t node = begin; node < end; ++node) {
        spline.weigh(lattice.nodes_m[node], row.data());
        for (std::size_t i = 0; i < n; ++i)
          skin.node_from_control_[i * skin.node_count_ + node] = static_cast<float>(row[i]);
      }
    });
    skin.nonnegative_weights_ = false;  // the spline's weights change sign between the points
    skin.storeSeparable(lattice.base, lattice.axis_weights, lattice.stride);
    // Only the nodes some vertex follows bound its motion: the outer ring, outside the control points,
    // extrapolates with larger sums and would loosen the bound the contact test culls with (the sedan at
    // 60 points: 6.4 over the followed nodes, 12.9 over all).
    std::vector<char> followed(skin.node_count_, 0);
    for (std::size_t j = 0; j < skin.vertex_count_; ++j)
      for (std::size_t k = 0; k < detail::kLatticeSlots; ++k) followed[skin.slotIndex(j, k)] = 1;
    for (std::size_t node = 0; node < skin.node_count_; ++node) {
      if (!followed[node]) continue;
      double gain = 0;
      for (std::size_t i = 0; i < n; ++i)
        gain += std::abs(static_cast<double>(skin.node_from_control_[i * skin.node_count_ + node]));
      skin.displacement_gain_ = std::max(skin.displacement_gain_, gain);
    }
    return skin;  // every vertex follows every point: no reverse index to keep
  }
  const std::size_t slots = skin.vertex_count_ * skin.influences_;
  // Built in float and 32-bit indices, then re-stored in the layout asked for (skin_layout.cpp).
  std::vector<uint32_t> built_indices(slots);
  std::vector<float> built_weights(slots);

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
      // mls: the (K+1)-th nearest too, at whose distance the fit's weights fall to zero (continuity).
      const std::size_t asked = options.method == SkinMethod::mls && K < n ? K + 1 : K;
      if (use_tree) {
        tree->nearest(v, asked, ranked);
      } else {
        ranked.clear();
        for (uint32_t i = 0; i < n; ++i) ranked.push_back({(control_rest_m[i] - v).squaredNorm(), i});
        if (asked < n)
          std::nth_element(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(asked - 1),
                           ranked.end());
        ranked.resize(asked);
        if (asked > K)  // the (K+1)-th nearest last
          std::iter_swap(std::max_element(ranked.begin(), ranked.end()), ranked.end() - 1);
      }
      double cutoff_m = 0;
      if (asked > K) {
        cutoff_m = std::sqrt(ranked.back().distance2_m2);
        ranked.pop_back();
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
      auto weigh = [&] {
        // Slots in index order: deterministic, and the displacement reads walk forward through memory.
        std::sort(ranked.begin(), ranked.end(),
                  [](const auto& a, const auto& b) { return a.index < b.index; });
        for (std::size_t k = 0; k < K; ++k) {
          chosen[k] = ranked[k].index;
          distance[k] = std::sqrt(ranked[k].distance2_m2);
          point[k] = control_rest_m[chosen[k]];
        }
        if (options.method != SkinMethod::mls) {
          detail::inverseDistanceWeights(distance.data(), K, options.alpha, weight.data());
          return true;
        }
        return detail::movingLeastSquaresWeights(v, point.data(), distance.data(), K, options.alpha,
                                                 weight.data(), cutoff_m);
      };
      // A fit that had to be bounded (a vertex a few millimetres off points thinner still, at fine N) is
      // not exact for affine maps: widen the points across their plane by their own extent and fit again.
      if (!weigh() && K < n) {
        candidates.clear();
        for (uint32_t i = 0; i < n; ++i) candidates.push_back({(control_rest_m[i] - v).squaredNorm(), i});
        std::sort(candidates.begin(), candidates.end());
        detail::widenSpan(v, control_rest_m, ranked, candidates, true);
        weigh();
      }
      for (std::size_t k = 0; k < K; ++k) {
        built_indices[j * K + k] = chosen[k];
        built_weights[j * K + k] = static_cast<float>(weight[k]);
      }
    }
  });
  skin.storeCompact(built_weights, built_indices);
  // v - v0 = sum_i w_i d_i, so |v - v0| <= (sum_i |w_i|) max_i |d_i|: 1 for idw, more for mls's
  // negative weights.
  for (std::size_t j = 0; j < skin.vertex_count_; ++j) {
    double gain = 0;
    for (std::size_t k = 0; k < K; ++k) {
      gain += std::abs(skin.slotWeight(j, k));
      skin.nonnegative_weights_ = skin.nonnegative_weights_ && skin.slotWeight(j, k) >= 0;
    }
    skin.displacement_gain_ = std::max(skin.displacement_gain_, gain);
  }
  // Reverse index (counting sort by control point); slots with zero weight (after rounding) influence
  // nothing.
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
  if (node_count_ > 0) {
    double through_nodes = 0;
    for (std::size_t k = 0; k < influences_; ++k)
      through_nodes += static_cast<double>(slotWeight(j, k)) *
                       static_cast<double>(node_from_control_[i * node_count_ + slotIndex(j, k)]);
    return static_cast<float>(through_nodes);
  }
  for (std::size_t k = 0; k < influences_; ++k)
    if (slotIndex(j, k) == i) return slotWeight(j, k);
  return 0.0f;
}

}  // namespace deform
