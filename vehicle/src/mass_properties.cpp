// Uniform-density solid integrals over a fan of signed tetrahedra.
#include <vehicle/mass_properties.hpp>

#include <deform/error.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace vehicle {

SolidProperties solidProperties(const std::vector<Eigen::Vector3d>& points,
                                const std::vector<std::array<uint32_t, 3>>& triangles, const char* source) {
  // Integrate about a point near the surface's middle (the vertex mean) to keep the sums well scaled far
  // from the origin.
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();
  for (const auto& p : points) reference += p;
  if (!points.empty()) reference /= static_cast<double>(points.size());
  double volume = 0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();
  for (const auto& t : triangles) {
    const Eigen::Vector3d a = points[t[0]] - reference, b = points[t[1]] - reference,
                          c = points[t[2]] - reference;
    const double v = a.dot(b.cross(c)) / 6.0;  // signed volume of the tetrahedron (0, a, b, c)
    const Eigen::Vector3d s = a + b + c;
    volume += v;
    first_moment += v * s / 4.0;
    second_moment +=
        v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  if (!(volume > 0) || !std::isfinite(volume))
    throw deform::InputError(std::string(source) +
                             ": surface encloses no volume (not closed or inward wound)");
  SolidProperties out;
  out.volume_m3 = volume;
  const Eigen::Vector3d centroid = first_moment / volume;
  out.centroid_m = reference + centroid;
  // Second moment about the centroid per unit volume, then the inertia tensor tr(C) 1 - C per kg.
  const Eigen::Matrix3d c = second_moment / volume - centroid * centroid.transpose();
  out.inertia_per_kg = c.trace() * Eigen::Matrix3d::Identity() - c;
  return out;
}

Eigen::Matrix3d shiftedInertia(const Eigen::Matrix3d& inertia_com_kg_m2, double mass_kg,
                               const Eigen::Vector3d& offset_m) {
  return inertia_com_kg_m2 +
         mass_kg * (offset_m.squaredNorm() * Eigen::Matrix3d::Identity() - offset_m * offset_m.transpose());
}

}  // namespace vehicle
