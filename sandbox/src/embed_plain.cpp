#include "embed_plain.hpp"

#include <deform/parallel.hpp>

namespace sandbox {

PlainSkin makePlainSkin(const deform::Skin& skin, const std::vector<Eigen::Vector3f>& rest_m) {
  PlainSkin plain;
  plain.influences = skin.influences();
  plain.rest_m.reserve(rest_m.size());
  for (const auto& v : rest_m) plain.rest_m.push_back({v.x(), v.y(), v.z()});
  const std::size_t K = plain.influences;
  plain.index.resize(skin.vertexCount() * K);
  plain.weight.resize(skin.vertexCount() * K);
  for (std::size_t j = 0; j < skin.vertexCount(); ++j)
    for (std::size_t k = 0; k < K; ++k) {
      plain.index[j * K + k] = static_cast<uint16_t>(skin.slotIndex(j, k));
      plain.weight[j * K + k] = skin.slotWeight(j, k);
    }
  return plain;
}

void plainSkinPass(const PlainSkin& skin, const std::vector<PlainPoint>& displacement_m,
                   std::vector<PlainPoint>& out_m, unsigned threads) {
  const std::size_t K = skin.influences;
  const PlainPoint* disp = displacement_m.data();
  deform::parallelFor(skin.rest_m.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j) {
      float dx = 0, dy = 0, dz = 0;
      const uint16_t* id = &skin.index[j * K];
      const float* w = &skin.weight[j * K];
      for (std::size_t k = 0; k < K; ++k) {
        const PlainPoint& d = disp[id[k]];
        dx += w[k] * d.x;
        dy += w[k] * d.y;
        dz += w[k] * d.z;
      }
      const PlainPoint& r = skin.rest_m[j];
      out_m[j] = {r.x + dx, r.y + dy, r.z + dz};
    }
  });
}

}  // namespace sandbox
