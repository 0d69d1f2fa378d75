#pragma once
// The plain K-sparse skin kernel the project's pass is measured against in the same run (issue 13): the
// way a competent engineer would first write it (float weights, 16-bit indices, a threaded loop, one
// 12-byte struct per position: 72 bytes per vertex at K = 8). Written here after the reference
// kernel (shared/bench/embed_ref.cpp), on the project's own weights and threads.
#include <deform/skin.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace sandbox {

struct PlainPoint {
  float x, y, z;
};

/// The skin's weights (as floats) and indices (16-bit) in the plain kernel's arrays.
struct PlainSkin {
  std::size_t influences = 0;
  std::vector<PlainPoint> rest_m;
  std::vector<uint16_t> index;
  std::vector<float> weight;
  std::size_t bytesPerVertex() const { return 2 * sizeof(PlainPoint) + influences * (2 + sizeof(float)); }
};

/// Copies `skin` (at most 65,536 control points) into the plain arrays.
PlainSkin makePlainSkin(const deform::Skin& skin, const std::vector<Eigen::Vector3f>& rest_m);

/// out_j = rest_j + sum_k w_jk d_(i_jk), on `threads` threads (0: every core), built and threaded as the
/// reference is: -march=native, an OpenMP static loop.
void plainSkinPass(const PlainSkin& skin, const std::vector<PlainPoint>& displacement_m,
                   std::vector<PlainPoint>& out_m, unsigned threads);

}  // namespace sandbox
