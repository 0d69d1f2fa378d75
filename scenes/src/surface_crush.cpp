#include <scenes/surface_crush.hpp>

#include <vehicle/simulation.hpp>

#include <deform/error.hpp>

#include <cmath>

namespace scenes {

SurfaceCrush surfaceCrush(const deform::Mesh& body, const std::vector<Eigen::Vector3f>& now_m,
                          const Eigen::Vector3d& direction) {
  if (now_m.size() != body.positions_m.size())
    throw deform::InputError("surfaceCrush: " + std::to_string(now_m.size()) + " positions for a mesh of " +
                             std::to_string(body.positions_m.size()) + " vertices");
  SurfaceCrush out;
  if (body.positions_m.empty()) return out;
  std::vector<Eigen::Vector3d> rest, now;
  rest.reserve(now_m.size());
  now.reserve(now_m.size());
  for (const auto& p : body.positions_m) rest.push_back(p.cast<double>());
  for (const auto& p : now_m) now.push_back(p.cast<double>());
  const Eigen::Vector3d along(direction.x(), direction.y(), 0);
  std::size_t lead = 0;
  for (std::size_t i = 1; i < rest.size(); ++i)
    if (rest[i].dot(along) > rest[lead].dot(along)) lead = i;
  out.height_m = rest[lead].z();
  out.profile_m = vehicle::crushProfile(body.triangles, rest, now, direction, out.height_m);
  double sum = 0;
  std::size_t hits = 0;
  for (double c : out.profile_m) {
    if (std::isnan(c)) continue;
    sum += c;
    ++hits;
    out.max_residual_crush_m = std::max(out.max_residual_crush_m, c);
  }
  out.residual_crush_m = hits ? sum / static_cast<double>(hits) : 0.0;
  return out;
}

}  // namespace scenes
