// Tetrahedral fan mass split (Kenwright 2015, Figure "Non-Linear Control Element Coupling").
#include <deform/error.hpp>
#include <deform/masses.hpp>

#include <cmath>
#include <string>

namespace deform {

double MassSplit::total_kg() const {
  double sum = core_mass_kg;
  for (double m : point_mass_kg) sum += m;
  return sum;
}

MassSplit distributeMass(const ControlMesh& mesh, double vehicle_mass_kg) {
  if (!std::isfinite(vehicle_mass_kg) || vehicle_mass_kg <= 0)
    throw InputError("vehicle mass must be finite and positive (got " + std::to_string(vehicle_mass_kg) +
                     " kg)");
  MassSplit split;
  split.point_mass_kg.assign(mesh.points_m.size(), 0.0);
  const Eigen::Vector3d& centre = mesh.centre_of_mass_m;
  // Tet volumes from the centre; they sum to the hull volume for a convex surface around the centre.
  std::vector<double> tet_volume(mesh.triangles.size());
  double total_volume = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    Eigen::Vector3d a = mesh.points_m[tri[0]] - centre, b = mesh.points_m[tri[1]] - centre,
                    c = mesh.points_m[tri[2]] - centre;
    tet_volume[t] = std::max(0.0, a.dot(b.cross(c)) / 6.0);
    total_volume += tet_volume[t];
  }
  if (!(total_volume > 0)) throw InputError("control mesh encloses no volume; cannot distribute mass");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const double quarter_kg = 0.25 * vehicle_mass_kg * tet_volume[t] / total_volume;
    for (uint32_t v : mesh.triangles[t]) split.point_mass_kg[v] += quarter_kg;
    split.core_mass_kg += quarter_kg;
  }
  // A symmetric body's control points are symmetric, but the diagonals a triangulation picks across
  // coplanar quads are not; each mirror pair shares its mass equally so the car stays balanced.
  if (mesh.mirror_of.size() == split.point_mass_kg.size()) {
    std::vector<double> balanced(split.point_mass_kg.size());
    for (std::size_t i = 0; i < balanced.size(); ++i)
      balanced[i] = 0.5 * (split.point_mass_kg[i] + split.point_mass_kg[mesh.mirror_of[i]]);
    split.point_mass_kg = std::move(balanced);
  }
  return split;
}

}  // namespace deform
