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
  // As the reference is built and run (g++ -O3 -march=native -fopenmp; an OpenMP static loop): this file
  // is compiled with -march=native and OpenMP (sandbox/CMakeLists.txt), the project's own pass is not.
  const long K = static_cast<long>(skin.influences);
  const PlainPoint* disp = displacement_m.data();
  const PlainPoint* rest = skin.rest_m.data();
  const uint16_t* index = skin.index.data();
  const float* weight = skin.weight.data();
  PlainPoint* out = out_m.data();
  const long count = static_cast<long>(skin.rest_m.size());
  const int team = static_cast<int>(deform::resolveThreads(threads));
#pragma omp parallel for schedule(static) num_threads(team)
  for (long j = 0; j < count; ++j) {
    float dx = 0, dy = 0, dz = 0;
    const uint16_t* id = &index[j * K];
    const float* w = &weight[j * K];
    for (long k = 0; k < K; ++k) {
      const PlainPoint& d = disp[id[k]];
      dx += w[k] * d.x;
      dy += w[k] * d.y;
      dz += w[k] * d.z;
    }
    out[j] = {rest[j].x + dx, rest[j].y + dy, rest[j].z + dz};
  }
}

}  // namespace sandbox
