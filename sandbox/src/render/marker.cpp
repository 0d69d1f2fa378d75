#include "render/marker.hpp"

#include <cmath>
#include <numbers>

namespace sandbox::render {

MeshData markerSphere(const Eigen::Vector3f& centre_m, float radius_m, const Eigen::Vector3f& colour) {
  // Latitude-longitude sphere with one vertex per pole; counter-clockwise seen from outside.
  constexpr uint32_t kRings = 10, kSegments = 20;
  deform::Mesh sphere;
  sphere.positions_m.emplace_back(0.0f, 0.0f, radius_m);
  for (uint32_t r = 1; r < kRings; ++r) {
    const double polar = std::numbers::pi * r / kRings;
    for (uint32_t s = 0; s < kSegments; ++s) {
      const double azimuth = 2.0 * std::numbers::pi * s / kSegments;
      sphere.positions_m.emplace_back(static_cast<float>(radius_m * std::sin(polar) * std::cos(azimuth)),
                                      static_cast<float>(radius_m * std::sin(polar) * std::sin(azimuth)),
                                      static_cast<float>(radius_m * std::cos(polar)));
    }
  }
  sphere.positions_m.emplace_back(0.0f, 0.0f, -radius_m);
  const uint32_t south = static_cast<uint32_t>(sphere.positions_m.size() - 1);
  const auto ring = [](uint32_t r, uint32_t s) { return 1 + (r - 1) * kSegments + s % kSegments; };
  for (uint32_t s = 0; s < kSegments; ++s) {
    sphere.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
    for (uint32_t r = 1; r + 1 < kRings; ++r) {
      sphere.triangles.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      sphere.triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
    sphere.triangles.push_back({ring(kRings - 1, s), south, ring(kRings - 1, s + 1)});
  }
  MeshData data = meshData(sphere, colour);
  data.model.block<3, 1>(0, 3) = centre_m;
  data.specular = 0.6f;
  return data;
}

}  // namespace sandbox::render
