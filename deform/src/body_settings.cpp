// Building a body's constraint arrays from its control mesh (DESIGN.md section 4).
#include <deform/body_settings.hpp>
#include <deform/error.hpp>

#include <Eigen/LU>
#include <cmath>
#include <string>

namespace deform {
namespace {

/// Index of the material of a constraint over `points`: the last region holding all of them.
template <std::size_t N>
uint32_t materialOf(const std::array<uint32_t, N>& points, const std::vector<std::vector<char>>& in_region) {
  for (std::size_t r = in_region.size(); r-- > 0;) {
    bool all = true;
    for (uint32_t p : points) all = all && in_region[r][p];
    if (all) return static_cast<uint32_t>(r + 1);
  }
  return 0;
}

void checkDeviation(double value, const std::string& field) {
  if (!std::isfinite(value) || value <= 0)
    throw InputError(field + ": must be finite and > 0 (got " + std::to_string(value) + " m)");
}

}  // namespace

BodySettings createBodySettings(const ControlMesh& mesh, const MassSplit& masses,
                                const BodyDescription& description) {
  const std::size_t n = mesh.points_m.size();
  if (n < 4)
    throw InputError("control mesh: needs at least 4 control points (got " + std::to_string(n) + ")");
  if (masses.point_mass_kg.size() != n)
    throw InputError("masses: " + std::to_string(masses.point_mass_kg.size()) + " point masses for " +
                     std::to_string(n) + " control points");
  checkMaterial(description.material, "material");
  checkDeviation(description.max_deviation_m, "max_deviation_m");

  BodySettings s;
  s.rest_positions_m = mesh.points_m;
  s.core_m = mesh.centre_of_mass_m;
  s.core_mass_kg = masses.core_mass_kg;

  double mean_kg = 0;
  for (double m : masses.point_mass_kg) {
    if (!std::isfinite(m) || m < 0) throw InputError("masses: point mass not finite and >= 0");
    mean_kg += m;
  }
  mean_kg /= static_cast<double>(n);
  if (!(mean_kg > 0)) throw InputError("masses: total point mass must be > 0");
  s.mass_kg.resize(n);
  s.inverse_mass_per_kg.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.mass_kg[i] = masses.point_mass_kg[i] > 0 ? masses.point_mass_kg[i] : 1e-3 * mean_kg;
    s.inverse_mass_per_kg[i] = 1.0 / s.mass_kg[i];
  }

  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d r = mesh.points_m[i] - s.core_m;
    inertia += s.mass_kg[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  // Control points not all on one line around the core: the inertia is invertible.
  s.shell_inverse_inertia = inertia.inverse();
  if (!s.shell_inverse_inertia.allFinite())
    throw InputError("control mesh: degenerate (no rotational inertia)");

  // Materials and region membership.
  s.materials.push_back(description.material);
  s.max_deviation_m.assign(n, description.max_deviation_m);
  std::vector<std::vector<char>> in_region;
  for (std::size_t r = 0; r < description.regions.size(); ++r) {
    const MaterialRegion& region = description.regions[r];
    const std::string field = "regions[" + std::to_string(r) + "]";
    checkMaterial(region.material, field + ".material");
    s.materials.push_back(region.material);
    std::vector<char> member(n, 0);
    if (region.box_m)
      for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d& p = mesh.points_m[i];
        member[i] = (p.array() >= region.box_m->min_m.array()).all() &&
                    (p.array() <= region.box_m->max_m.array()).all();
      }
    for (uint32_t p : region.points) {
      if (p >= n) throw InputError(field + ".points: index " + std::to_string(p) + " out of range");
      member[p] = 1;
    }
    if (!std::isnan(region.max_deviation_m)) {
      checkDeviation(region.max_deviation_m, field + ".max_deviation_m");
      for (std::size_t i = 0; i < n; ++i)
        if (member[i]) s.max_deviation_m[i] = region.max_deviation_m;
    }
    in_region.push_back(std::move(member));
  }
  for (std::size_t k = 0; k < description.max_deviation_overrides.size(); ++k) {
    const auto& [p, radius] = description.max_deviation_overrides[k];
    const std::string field = "max_deviation_overrides[" + std::to_string(k) + "]";
    if (p >= n) throw InputError(field + ": index " + std::to_string(p) + " out of range");
    checkDeviation(radius, field);
    s.max_deviation_m[p] = radius;
  }
  for (const Material& m : s.materials)
    s.plastic_laws.push_back({m.yield_strain, m.hardening, m.min_rest_fraction, m.max_rest_fraction});

  for (const auto& t : mesh.triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) throw InputError("control mesh: triangle index out of range");
  }
  s.triangles = mesh.triangles;

  // Constraint arrays, in mesh order (deterministic).
  for (const ControlEdge& e : mesh.edges) {
    if (e.a >= n || e.b >= n || e.left >= n || e.right >= n)
      throw InputError("control mesh: edge index out of range");
    const uint32_t edge_material = materialOf<2>({e.a, e.b}, in_region);
    s.edges.push_back({e.a, e.b, edge_material, s.materials[edge_material].edge_compliance_m_per_N});
    s.edge_rest_m.push_back((mesh.points_m[e.a] - mesh.points_m[e.b]).norm());
    if (e.left == e.right) continue;  // an open edge has no bend
    // A bend across a nearly flat hinge adds no first-order bending stiffness (its gradient lies in the
    // plane the edges already hold) but makes the four points a flat tetrahedron with all six distances
    // fixed: ill-conditioned, it jitters under Gauss-Seidel. Such hinges get no bend.
    const Eigen::Vector3d& pa = mesh.points_m[e.a];
    const Eigen::Vector3d& pb = mesh.points_m[e.b];
    const Eigen::Vector3d n1 = (pb - pa).cross(mesh.points_m[e.left] - pa);
    const Eigen::Vector3d n2 = (pa - pb).cross(mesh.points_m[e.right] - pb);
    const double fold_rad = std::atan2(n1.cross(n2).norm(), n1.dot(n2));
    if (!(fold_rad >= description.min_bend_fold_rad)) continue;
    const uint32_t bend_material = materialOf<4>({e.a, e.b, e.left, e.right}, in_region);
    s.bends.push_back(
        {e.left, e.right, e.a, e.b, bend_material, s.materials[bend_material].bend_compliance_m_per_N});
    s.bend_rest_m.push_back((mesh.points_m[e.left] - mesh.points_m[e.right]).norm());
  }
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t material = materialOf<1>({i}, in_region);
    s.spokes.push_back({i, material, s.materials[material].spoke_compliance_m_per_N});
    s.spoke_rest_m.push_back((mesh.points_m[i] - s.core_m).norm());
  }
  return s;
}

}  // namespace deform
