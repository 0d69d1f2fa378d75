// Building a body's constraint arrays from its control mesh (DESIGN.md section 4).
#include <deform/body_settings.hpp>
#include <deform/error.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "material_field.hpp"
#include "sweep_order.hpp"

namespace deform {
namespace {

using detail::MaterialField;
using detail::MaterialShares;

/// A constraint over `points` all listed by one region (by index) takes that region's material alone (the
/// last such region); otherwise its shares of the material field over its skin, normalised.
template <std::size_t N>
MaterialShares sharesOf(const std::array<uint32_t, N>& points, const std::vector<std::vector<char>>& listed,
                        MaterialShares shares) {
  for (std::size_t r = listed.size(); r-- > 0;) {
    if (listed[r].empty()) continue;
    bool all = true;
    for (uint32_t p : points) all = all && listed[r][p];
    if (all) {
      std::fill(shares.begin(), shares.end(), 0.0);
      shares[r + 1] = 1.0;
      return shares;
    }
  }
  MaterialField::normalise(shares);
  return shares;
}

/// sum_r share_r * member(material_r), as the default's value plus each region's difference from it, so
/// a patch whose regions all hold the default's value gets that value to the last bit.
template <typename Member>
double blend(const MaterialShares& shares, const std::vector<Material>& materials, Member member) {
  const double base = member(materials[0]);
  double difference = 0;
  for (std::size_t r = 1; r < shares.size(); ++r)
    if (shares[r] > 0) difference += shares[r] * (member(materials[r]) - base);
  return base + difference;
}

/// Compliance [m/N] of a constraint of stiffness `stiffness_N_per_m`; a constraint without stiffness is
/// given a compliance so large that it carries no load (XPBD has no infinite compliance).
double complianceOf(double stiffness_N_per_m) {
  constexpr double kSlack_m_per_N = 1e3;
  return stiffness_N_per_m > 1.0 / kSlack_m_per_N ? 1.0 / stiffness_N_per_m : kSlack_m_per_N;
}

/// Area of the triangle (a, b, c) [m^2].
double area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

void checkDeviation(double value, const std::string& field) {
  if (!std::isfinite(value) || value <= 0)
    throw InputError(field + ": must be finite and > 0 (got " + std::to_string(value) + " m)");
}

template <class T>
void permute(std::vector<T>& values, const std::vector<uint32_t>& order) {
  std::vector<T> out;
  out.reserve(order.size());
  for (uint32_t k : order) out.push_back(values[k]);
  values = std::move(out);
}

/// Puts the edges and the bends in sweep order (sweep_order.hpp): the body's two halves, then the
/// constraints across the cut.
void putInSweepOrder(BodySettings& s) {
  const std::vector<uint8_t> halves = bodyHalves(s.rest_positions_m);
  std::vector<std::array<uint32_t, 2>> pairs;
  for (const EdgeConstraint& e : s.edges) pairs.push_back({e.a, e.b});
  SweepOrder sweep = sweepOrder(pairs, halves);
  permute(s.edges, sweep.order);
  permute(s.edge_rest_m, sweep.order);
  permute(s.edge_yield, sweep.order);
  s.edge_half_end = sweep.half_end;
  pairs.clear();
  for (const BendConstraint& b : s.bends) pairs.push_back({b.left, b.right});
  sweep = sweepOrder(pairs, halves);
  permute(s.bends, sweep.order);
  permute(s.bend_rest_m, sweep.order);
  permute(s.bend_yield, sweep.order);
  s.bend_half_end = sweep.half_end;
  s.column_order.clear();
  for (int half : {0, 1})
    for (uint32_t k = 0; k < s.spokes.size(); ++k)
      if (halves[s.spokes[k].point] == half) s.column_order.push_back(k);
  s.column_half_end = static_cast<uint32_t>(std::count_if(
      s.spokes.begin(), s.spokes.end(), [&](const SpokeConstraint& c) { return halves[c.point] == 0; }));
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
  s.anchored_columns = description.anchored_columns;

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
  std::vector<std::vector<char>> listed;  // per region, the points it selects by index (empty: none)
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
    std::vector<char> by_index(region.points.empty() ? 0 : n, 0);
    for (uint32_t p : region.points) {
      if (p >= n) throw InputError(field + ".points: index " + std::to_string(p) + " out of range");
      member[p] = 1;
      by_index[p] = 1;
    }
    if (!std::isnan(region.max_deviation_m)) {
      checkDeviation(region.max_deviation_m, field + ".max_deviation_m");
      for (std::size_t i = 0; i < n; ++i)
        if (member[i]) s.max_deviation_m[i] = region.max_deviation_m;
    }
    listed.push_back(std::move(by_index));
  }
  for (std::size_t k = 0; k < description.max_deviation_overrides.size(); ++k) {
    const auto& [p, radius] = description.max_deviation_overrides[k];
    const std::string field = "max_deviation_overrides[" + std::to_string(k) + "]";
    if (p >= n) throw InputError(field + ": index " + std::to_string(p) + " out of range");
    checkDeviation(radius, field);
    s.max_deviation_m[p] = radius;
  }
  for (const Material& m : s.materials)
    s.plastic_laws.push_back({m.hardening, m.min_rest_fraction, m.max_rest_fraction});

  for (const auto& t : mesh.triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) throw InputError("control mesh: triangle index out of range");
  }
  s.triangles = mesh.triangles;
  s.triangle_across = triangleNeighbours(s.triangles);

  // Tributary areas: a third of each triangle's area (as a vector, along its outward normal) to each of
  // its corners.
  s.tributary_area_m2.assign(n, 0.0);
  std::vector<Eigen::Vector3d> vector_area(n, Eigen::Vector3d::Zero());
  // The material field over each point's patch (its third of each triangle, by the hat function).
  const MaterialField field(description.regions);
  const MaterialShares no_shares(s.materials.size(), 0.0);
  std::vector<MaterialShares> patch_shares(field.hasBoxes() ? n : 0, no_shares);
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.points_m[t[0]];
    const Eigen::Vector3d third =
        (mesh.points_m[t[1]] - a).cross(mesh.points_m[t[2]] - a) / 6.0;  // area vector / 3
    for (uint32_t corner : t) vector_area[corner] += third;
    if (field.hasBoxes())
      for (int k = 0; k < 3; ++k)
        field.addTriangle(a, mesh.points_m[t[1]], mesh.points_m[t[2]], k,
                          patch_shares[t[static_cast<std::size_t>(k)]]);
  }
  // Constraint arrays, in mesh order (deterministic), put in sweep order at the end (putInSweepOrder).
  for (const ControlEdge& e : mesh.edges) {
    if (e.a >= n || e.b >= n || e.left >= n || e.right >= n)
      throw InputError("control mesh: edge index out of range");
    const Eigen::Vector3d& pa = mesh.points_m[e.a];
    const Eigen::Vector3d& pb = mesh.points_m[e.b];
    const Eigen::Vector3d& pl = mesh.points_m[e.left];
    const Eigen::Vector3d& pr = mesh.points_m[e.right];
    const double length = (pa - pb).norm();
    const double wings_area = area(pa, pb, pl) + (e.left == e.right ? 0.0 : area(pb, pa, pr));
    // A membrane strip (Van Gelder 1998): k = E t (A_left + A_right) / L^2; it yields at the membrane
    // force per unit width times the strip's width, (A_left + A_right) / L.
    // The strip's material: the field over both wings (springs side by side: their moduli add).
    MaterialShares wing_shares = no_shares;
    if (field.hasBoxes()) {
      field.addTriangle(pa, pb, pl, -1, wing_shares);
      if (e.left != e.right) field.addTriangle(pb, pa, pr, -1, wing_shares);
    }
    const MaterialShares strip = sharesOf<2>({e.a, e.b}, listed, wing_shares);
    const auto& materials = s.materials;
    const double safe_length = std::max(length, kMinConstraintLength_m);
    const double edge_stiffness =
        blend(strip, materials, [](const Material& m) { return m.shell_stiffness_N_per_m; }) * wings_area /
        (safe_length * safe_length);
    const double edge_compliance = complianceOf(edge_stiffness);
    const double strip_width_m = wings_area / safe_length;
    s.edges.push_back({e.a, e.b, MaterialField::dominant(strip), edge_compliance});
    s.edge_rest_m.push_back(length);
    s.edge_yield.push_back(
        {blend(strip, materials, [](const Material& m) { return m.shell_tension_yield_N_per_m; }) *
             strip_width_m * edge_compliance,
         blend(strip, materials, [](const Material& m) { return m.shell_compression_yield_N_per_m; }) *
             strip_width_m * edge_compliance});
    if (e.left == e.right) continue;  // an open edge has no bend
    // A bend across a nearly flat hinge adds no first-order bending stiffness (its gradient lies in the
    // plane the edges already hold) but makes the four points a flat tetrahedron with all six distances
    // fixed: ill-conditioned, it jitters under Gauss-Seidel. Such hinges get no bend.
    const Eigen::Vector3d n1 = (pb - pa).cross(pl - pa);
    const Eigen::Vector3d n2 = (pa - pb).cross(pr - pb);
    const double fold_rad = std::atan2(n1.cross(n2).norm(), n1.dot(n2));
    if (!(fold_rad >= description.min_bend_fold_rad)) continue;
    // Hinge stiffness k_theta = 6 D |e|^2 / (A_left + A_right) (Grinspun et al. 2003, "Discrete Shells":
    // W = k_B (theta - theta0)^2 3 |e|^2 / A_e), taken to the wing distance d: with the wings' distances
    // h_l, h_r from the hinge line and the dihedral angle phi = pi - fold, dd/dphi = h_l h_r sin(phi) / d,
    // so the distance stiffness is k_theta / (dd/dphi)^2 and the plastic moment m_p |e| is the force
    // m_p |e| / (dd/dphi).
    const Eigen::Vector3d axis = (pb - pa) / safe_length;
    const Eigen::Vector3d ql = pl - pa, qr = pr - pa;
    const double h_left = (ql - ql.dot(axis) * axis).norm();
    const double h_right = (qr - qr.dot(axis) * axis).norm();
    const double wing_distance = (pl - pr).norm();
    const double lever_m =
        h_left * h_right * std::sin(fold_rad) / std::max(wing_distance, kMinConstraintLength_m);
    const MaterialShares hinge = sharesOf<4>({e.a, e.b, e.left, e.right}, listed, wing_shares);
    const double bending_stiffness_N_m =
        blend(hinge, materials, [](const Material& m) { return m.shell_bending_stiffness_N_m; });
    const double yield_moment_N =
        blend(hinge, materials, [](const Material& m) { return m.shell_yield_moment_N; });
    const double hinge_stiffness_N_m = 6.0 * bending_stiffness_N_m * length * length / wings_area;
    const double bend_stiffness = lever_m > 0 ? hinge_stiffness_N_m / (lever_m * lever_m) : 0.0;
    const double bend_compliance = complianceOf(bend_stiffness);
    const double bend_yield_m = lever_m > 0 ? yield_moment_N * length / lever_m * bend_compliance : 0.0;
    s.bends.push_back({e.left, e.right, e.a, e.b, MaterialField::dominant(hinge), bend_compliance});
    s.bend_rest_m.push_back(wing_distance);
    s.bend_yield.push_back({bend_yield_m, bend_yield_m});
  }
  for (uint32_t i = 0; i < n; ++i) {
    // A column of the crushable structure behind the point's patch of skin, along the patch's normal
    // n = a / |a| (a: its vector area) from the point to the foot of the core on that line, as wide as
    // the patch seen along it, |a|: it yields at crush_strength |a| after the strain crush_yield_strain,
    // so k = strength |a| / (e_y L0). A flat obstacle pressing along d then meets strength x (a . d)
    // summed over the points it pushes: the pressure on the area it covers, at any N.
    // Columns side by side under the patch: their yield forces add, and so do their stiffnesses.
    const MaterialShares patch = sharesOf<1>({i}, listed, field.hasBoxes() ? patch_shares[i] : no_shares);
    const Eigen::Vector3d& p = mesh.points_m[i];
    const double area_m2 = vector_area[i].norm();
    Eigen::Vector3d anchor = s.core_m;
    s.spoke_normal.push_back(area_m2 > 0 ? Eigen::Vector3d(vector_area[i] / area_m2)
                                         : Eigen::Vector3d::Zero());
    if (area_m2 > 0) {
      const Eigen::Vector3d normal = vector_area[i] / area_m2;
      const double depth_m = normal.dot(p - s.core_m);  // > 0: the core is behind the patch
      if (depth_m > 0) anchor = p - depth_m * normal;
    }
    s.tributary_area_m2[i] = area_m2;
    const double length = (p - anchor).norm();
    const double yield_force_N =
        blend(patch, s.materials, [](const Material& m) { return m.crush_strength_Pa; }) * area_m2;
    // Columns of one material: k = F_y / (e_y L0). Of several side by side: their stiffnesses add.
    const uint32_t material = MaterialField::dominant(patch);
    const double yield_m = s.materials[material].crush_yield_strain * length;
    const double stiffness_N_per_m =
        patch[material] == 1.0 ? (yield_m > 0 ? yield_force_N / yield_m : 0.0)
        : length > 0           ? blend(patch, s.materials,
                                       [](const Material& m) { return m.crush_strength_Pa / m.crush_yield_strain; }) *
                           area_m2 / length
                     : 0.0;
    const double compliance = complianceOf(stiffness_N_per_m);
    s.spokes.push_back({i, material, compliance});
    s.spoke_rest_m.push_back(length);
    s.spoke_anchor_m.push_back(anchor - s.core_m);
    s.spoke_yield.push_back({yield_force_N * compliance, yield_force_N * compliance});
  }
  putInSweepOrder(s);
  return s;
}

}  // namespace deform
