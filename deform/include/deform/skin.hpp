#pragma once
// The embedding of the render mesh in the control points: v'_j = v_j + sum_i w_ij (c_i - c_i0), the weights
// over the K nearest control points computed once ("precompute, then solve"); the per-frame pass only
// reads them. Two choices of weights (SkinMethod):
//   idw: phi_ij = 1 / |c_i0 - v_j|^alpha normalised so that sum_i phi_ij = 1 (Kenwright 2015, equation 1):
//        reproduces a translation of the control points, not a rotation, stretch or shear;
//   mls: moving least squares with an affine fit, the same inverse distances as its weight less the one
//        the (K+1)-th nearest point would have, so that the weights are continuous where the K nearest
//        change (Schaefer, McPhail & Warren 2006, affine case): sum_i w_ij = 1 and sum_i w_ij c_i0 = v_j, so
//        any affine motion of the control points moves the vertices by that same map (linear precision);
//   spline: the cubic polyharmonic spline through every control point with a linear part (Duchon 1977),
//        evaluated each frame at the nodes of a lattice around the mesh, each vertex following the 27
//        nodes around it by quadratic B-spline weights: affine maps exact, continuously differentiable,
//        stored as 9 non-negative axis weights per vertex.
#include <deform/parallel.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace deform {

/// How the weights of a vertex are chosen from its K nearest control points.
enum class SkinMethod : uint8_t {
  idw,  ///< normalised inverse distance (Kenwright 2015): translations only; weights in [0, 1]
  mls,  ///< moving least squares, affine (Schaefer et al. 2006): affine maps exact; weights may be < 0
  /// Cubic polyharmonic spline with a linear part through all N points (Duchon 1977), through a lattice:
  /// affine maps exact; 27 slots per vertex over lattice nodes whatever k_nearest says, alpha not read;
  /// at most kSplineMostControlPoints.
  spline,
};

/// The most control points a spline skin takes: each frame that moves a point evaluates the spline at
/// every lattice node from every control point (5,775 nodes x N on the sedan), and its build solves a
/// dense (N + 4) system.
inline constexpr std::size_t kSplineMostControlPoints = 256;

/// "idw", "mls" or "spline"; the name of a method.
const char* skinMethodName(SkinMethod method);
/// The method named `name` ("idw", "mls" or "spline"), or false when there is none.
bool parseSkinMethod(const std::string& name, SkinMethod& method);

/// The largest level of detail at which mls is the better skin [control points]. On the built-in sedan
/// (`sandbox tradeoff --skin-only`, K = 8, alpha 3.5; docs/TRADEOFF.md) mls has the lower RMS and the
/// lower largest vertex error on every field at 60 points (the real crash's dent: 24.0 mm RMS, 185 mm
/// largest, against idw's 30.0 and 218). At 120 points its RMS is still lower (8.8 against 12.3 mm) but
/// its largest error is not (137 against 86 mm), and from 250 points its affine fit extrapolates the
/// dent's edge to vertices set back from the hull (RMS 14.7 against 11.7 mm at 250, 27.7 against 3.6 at
/// 2,000).
inline constexpr std::size_t kMlsUpToControlPoints = 60;

/// The fewest nearest points mls needs to be the better skin. With K = 4 its affine fit through four
/// points interpolates them and extrapolates freely: after the 56 km/h wall crash at 60 points it carries
/// vertices at the bonnet's rear 0.70 m where no control point moves more than 0.49 m, and it is worse
/// than idw at K = 4 on both of `sandbox tradeoff`'s scenes (wall_crash 37.2 against 32.0 mm RMS, 590
/// against 298 mm largest; post_bumps 22.5 against 19.7 mm RMS; docs/TRADEOFF.md). At K = 8, 16 and
/// dense it is the better one.
inline constexpr std::size_t kMlsFromNearest = 8;

/// The skin measured best at `control_points` with `k_nearest` points per vertex (0: every point), what
/// the skin method `auto` chooses: mls up to kMlsUpToControlPoints points with at least kMlsFromNearest
/// nearest points (or dense weights), idw otherwise (a scene's K = 4 gets idw; the presets have K = 8).
SkinMethod preferredSkinMethod(std::size_t control_points, std::size_t k_nearest);

/// How a skin stores its weights (Skin::build). The per-frame pass is memory-bound (docs/BENCHMARKS.md):
/// its cost follows the bytes it reads per vertex, so the compact form is the default.
enum class SkinLayout : uint8_t {
  /// Fixed-point weights whose integers sum exactly to the scale (so exactly to one), 8-bit indices up to
  /// 256 control points: idw 16-bit weights (scale 65,535), 3 bytes a slot; mls (negative weights) a
  /// signed 24-bit weight packed with its 8-bit index, 4 bytes a slot (mls past 256 points: float weights).
  compact,
  /// Float weights and 16-bit indices (32-bit past 65,536 points), 6 bytes a slot: the layout before.
  float_weights,
};

/// How the skin's weights are built (Skin::build).
struct SkinOptions {
  double alpha = 3.5;                       ///< inverse-distance power (paper: about 3-4); 0.5 .. 16 tested
  std::size_t k_nearest = 8;                ///< influences per vertex; 0 means dense (every control point)
  unsigned threads = 0;                     ///< worker threads for build and deform; 0 = hardware concurrency
  SkinMethod method = SkinMethod::idw;      ///< how the weights are chosen (idw: the paper's)
  SkinLayout layout = SkinLayout::compact;  ///< how they are stored
};

/// Weights of every render-mesh vertex: `influences()` slots per vertex, vertex-major, each slot a
/// control-point index and a weight. Slots past the used ones carry weight 0 (index 0).
class Skin {
 public:
  /// Throws InputError for alpha outside (0, 64], no control points or a non-finite position, and for a
  /// spline past kSplineMostControlPoints points or on points that do not span three dimensions.
  static Skin build(const std::vector<Eigen::Vector3f>& vertices_m,
                    const std::vector<Eigen::Vector3d>& control_rest_m, const SkinOptions& options);

  std::size_t vertexCount() const { return vertex_count_; }
  std::size_t controlPointCount() const { return control_count_; }
  std::size_t influences() const { return influences_; }
  double alpha() const { return alpha_; }
  SkinMethod method() const { return method_; }
  SkinLayout layout() const { return layout_; }
  /// Control point of slot k of vertex j (0 <= k < influences()); for a spline skin, the lattice node.
  uint32_t slotIndex(std::size_t j, std::size_t k) const;
  /// Weight of slot k of vertex j: slotWeightFixed / weightScale in the fixed-point forms.
  float slotWeight(std::size_t j, std::size_t k) const;
  /// Whether the weights are fixed point (their integers of a vertex sum exactly to weightScale()).
  bool fixedPointWeights() const { return weight_format_ != WeightFormat::float32; }
  /// The fixed-point integer of slot k of vertex j (0 for float weights).
  int64_t slotWeightFixed(std::size_t j, std::size_t k) const;
  /// The integer that stands for a weight of one (1 for float weights).
  int64_t weightScale() const { return weight_scale_; }
  /// Bytes per slot of the index (1, 2 or 4).
  std::size_t indexBytes() const { return index_bytes_; }
  /// Weight of control point `i` on vertex `j` (0 when not among its influences); for a spline skin, the
  /// spline's weight through the lattice (every point has one).
  float weight(std::size_t j, uint32_t i) const;
  /// Lattice nodes a spline skin's slots refer to (0 for idw and mls).
  std::size_t latticeNodeCount() const { return node_count_; }
  /// A bound on sum_i |w_ij| over the vertices: |v_j - v_j0| <= displacementGain() x max_i |d_i|. 1 for idw;
  /// mls's largest slot sum; for the spline the largest sum over the nodes any vertex follows (its
  /// B-spline weights are a convex combination of those nodes, whose own weights change sign).
  double displacementGain() const { return displacement_gain_; }
  /// Whether every control point's weight on every vertex is >= 0 (idw): a vertex moves within its
  /// points' hull.
  bool nonnegativeWeights() const { return nonnegative_weights_; }
  /// Bytes of the weights and indices.
  std::size_t memoryBytes() const;
  /// Bytes of the reverse index deformMoved uses (vertices each control point influences).
  std::size_t reverseIndexBytes() const;
  /// Bytes one deform pass reads and writes per vertex (rest position, slots, output).
  std::size_t bytesPerVertex() const;

  /// v'_j = v_j + sum_i w_ij d_i for every vertex, where d_i = c_i - c_i0 are the control-point
  /// displacements [m] (controlPointCount() of them). Same result for any thread count.
  void deform(const Eigen::Vector3f* rest_m, const Eigen::Vector3d* displacement_m, Eigen::Vector3f* out_m,
              unsigned threads = 0) const;

  /// Partial update (DESIGN.md section 8: only what moved is recomputed): re-deforms only the vertices
  /// that a control point flagged in `moved` (one flag per control point) influences, and leaves every
  /// other vertex of `out_m` as it is. Equal to a full deform() when `out_m` held the previous result and
  /// `moved` flags every point whose displacement changed since. Returns the vertices recomputed; when
  /// `recomputed` is given it receives one flag per vertex, 1 for those recomputed.
  std::size_t deformMoved(const Eigen::Vector3f* rest_m, const Eigen::Vector3d* displacement_m,
                          const std::vector<uint8_t>& moved, Eigen::Vector3f* out_m, unsigned threads = 0,
                          std::vector<uint8_t>* recomputed = nullptr) const;

 private:
  enum class WeightFormat : uint8_t { float32, unorm16, packed24, separable };
  /// The pass over vertices [begin, end); `scaled_xyz0` holds d_i / weightScale() as x, y, z, 0 floats.
  void deformRange(const Eigen::Vector3f* rest_m, const float* scaled_xyz0, Eigen::Vector3f* out_m,
                   std::size_t begin, std::size_t end) const;
  /// What the slots read: d_i / weightScale() as x, y, z, 0 floats per control point, or for a spline
  /// skin the spline at each lattice node in metres (its pass scales its own weights).
  std::vector<float, Eigen::aligned_allocator<float>> slotTable(const Eigen::Vector3d* displacement_m,
                                                                unsigned threads) const;
  /// The spline's lattice weights, kept separable (any layout): 9 unorm16 per vertex, each axis's three
  /// summing exactly to 65,535, and the first node's index.
  void storeSeparable(const std::vector<uint32_t>& base, const std::vector<float>& axis_weights,
                      const uint32_t stride[3]);
  /// The float weights (as built) re-stored in the layout asked for.
  void storeCompact(const std::vector<float>& weights, const std::vector<uint32_t>& indices);

  std::size_t vertex_count_ = 0;
  std::size_t control_count_ = 0;
  std::size_t influences_ = 0;
  double alpha_ = 0;
  SkinMethod method_ = SkinMethod::idw;
  SkinLayout layout_ = SkinLayout::compact;
  WeightFormat weight_format_ = WeightFormat::float32;
  uint8_t index_bytes_ = 2;
  int64_t weight_scale_ = 1;
  // Slots, vertex-major; only the arrays of the chosen form are filled.
  std::vector<uint8_t> indices8_;    ///< up to 256 control points
  std::vector<uint16_t> indices16_;  ///< up to 65,536
  std::vector<uint32_t> indices32_;  ///< more
  std::vector<float> weights_;       ///< float32: each vertex's sum is 1 to rounding (mls: some < 0)
  std::vector<uint16_t> weights16_;  ///< unorm16: weight x 65,535, each vertex's sum exactly 65,535
  std::vector<uint32_t> packed_;     ///< packed24: (weight x scale) << 8 | index, signed 24-bit weight
  /// Spline: node_count_ lattice nodes and the spline's weight of each control point on each (point-major:
  /// point i's weights on the nodes from i x node_count_); the slots then index nodes.
  std::size_t node_count_ = 0;
  std::vector<float> node_from_control_;  ///< float: 6e-8 of a weight
  /// separable: per vertex its first node and 9 axis weights (x's three, y's, z's) x 65,535; slot k is
  /// node base + (k % 3) stride[0] + (k / 3 % 3) stride[1] + (k / 9) stride[2], of weight the product.
  std::vector<uint32_t> lattice_base_;
  std::vector<uint16_t> lattice_weights_;
  uint32_t lattice_stride_[3] = {1, 1, 1};
  double displacement_gain_ = 1;
  bool nonnegative_weights_ = true;
  /// Reverse index for partial updates: the vertices control point i influences are
  /// influenced_vertices_[influenced_begin_[i] .. influenced_begin_[i + 1]).
  std::vector<std::size_t> influenced_begin_;
  std::vector<uint32_t> influenced_vertices_;
};

}  // namespace deform
