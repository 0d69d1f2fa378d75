#include <deform/error.hpp>
#include <deform/mesh.hpp>

#include <cmath>
#include <string>

namespace deform {

Aabb boundingBox(const Mesh& mesh) {
  Aabb box;
  if (mesh.positions_m.empty()) return box;
  box.min_m = box.max_m = mesh.positions_m.front().cast<double>();
  for (const auto& p : mesh.positions_m) {
    box.min_m = box.min_m.cwiseMin(p.cast<double>());
    box.max_m = box.max_m.cwiseMax(p.cast<double>());
  }
  return box;
}

void checkMesh(const Mesh& mesh, std::string_view source) {
  const std::string where(source);
  if (mesh.positions_m.empty()) throw InputError(where + ": no vertices");
  if (mesh.triangles.empty()) throw InputError(where + ": no triangles");
  for (std::size_t i = 0; i < mesh.positions_m.size(); ++i) {
    if (!mesh.positions_m[i].allFinite())
      throw InputError(where + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  }
  const std::size_t n = mesh.positions_m.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (uint32_t v : mesh.triangles[t]) {
      if (v >= n)
        throw InputError(where + ": triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) +
                         " of " + std::to_string(n));
    }
  }
  if (!mesh.normals.empty() && mesh.normals.size() != n)
    throw InputError(where + ": " + std::to_string(mesh.normals.size()) + " normals for " +
                     std::to_string(n) + " vertices");
  if (boundingBox(mesh).diagonal_m() <= 0) throw InputError(where + ": zero extent (all vertices coincide)");
}

void appendMesh(Mesh& mesh, const Mesh& part) {
  const auto offset = static_cast<uint32_t>(mesh.positions_m.size());
  const bool normals =
      mesh.normals.size() == mesh.positions_m.size() && part.normals.size() == part.positions_m.size();
  mesh.positions_m.insert(mesh.positions_m.end(), part.positions_m.begin(), part.positions_m.end());
  if (normals)
    mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
  else
    mesh.normals.clear();
  for (const auto& t : part.triangles)
    mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace deform
