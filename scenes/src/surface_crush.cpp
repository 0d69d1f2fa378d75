#include <scenes/surface_crush.hpp>

#include <deform/error.hpp>

#include <string>

namespace scenes {

vehicle::CrushStations surfaceCrush(const deform::Mesh& body, const std::vector<Eigen::Vector3f>& now_m,
                                    const Eigen::Vector3d& direction) {
  if (now_m.size() != body.positions_m.size())
    throw deform::InputError("surfaceCrush: " + std::to_string(now_m.size()) + " positions for a mesh of " +
                             std::to_string(body.positions_m.size()) + " vertices");
  std::vector<Eigen::Vector3d> rest, now;
  rest.reserve(now_m.size());
  now.reserve(now_m.size());
  for (const auto& p : body.positions_m) rest.push_back(p.cast<double>());
  for (const auto& p : now_m) now.push_back(p.cast<double>());
  return vehicle::crushStations(body.triangles, rest, now, direction);
}

}  // namespace scenes
