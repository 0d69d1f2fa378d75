// The sedan's material map and its placement on a car (material_map.hpp).
#include <deform/body_settings.hpp>
#include <deform/error.hpp>
#include <vehicle/material_map.hpp>

#include <algorithm>

namespace vehicle {
namespace {

deform::Aabb fractions(double x0, double y0, double z0, double x1, double y1, double z1) {
  return {{x0, y0, z0}, {x1, y1, z1}};
}

/// A fraction at the edge of the bounding box reaches beyond it, so the skin on the box's faces is in.
double reach(double fraction) {
  constexpr double kBeyond = 0.01;
  return fraction <= 0 ? -kBeyond : fraction >= 1 ? 1 + kBeyond : fraction;
}

}  // namespace

const std::vector<MaterialMember>& materialMembers() {
  using M = deform::Material;
  static const std::vector<MaterialMember> members = {
      {"crush_strength_Pa", &M::crush_strength_Pa, 0, 1e9},
      {"crush_yield_strain", &M::crush_yield_strain, 1e-6, 1},
      {"shell_stiffness_N_per_m", &M::shell_stiffness_N_per_m, 1, 1e12},
      {"shell_tension_yield_N_per_m", &M::shell_tension_yield_N_per_m, 0, 1e10},
      {"shell_compression_yield_N_per_m", &M::shell_compression_yield_N_per_m, 0, 1e10},
      {"shell_bending_stiffness_N_m", &M::shell_bending_stiffness_N_m, 0, 1e9},
      {"shell_yield_moment_N", &M::shell_yield_moment_N, 0, 1e9},
      {"hardening", &M::hardening, 0, 100},
  };
  return members;
}

bool RegionMaterial::set(const std::string& key, double value) {
  for (const MaterialMember& m : materialMembers()) {
    if (key != m.key) continue;
    for (auto& [member, v] : values)
      if (member == &m) {
        v = value;
        return true;
      }
    values.emplace_back(&m, value);
    return true;
  }
  return false;
}

std::optional<double> RegionMaterial::get(const std::string& key) const {
  for (const auto& [member, v] : values)
    if (key == member->key) return v;
  return std::nullopt;
}

std::vector<RegionMaterial> sedanMaterialMap() {
  std::vector<RegionMaterial> map;
  // The front and rear crush zones (longitudinal rails, engine bay, boot floor): the car's own material,
  // which the 56 km/h full-width barrier calibrates.
  map.push_back({"bonnet", {fractions(0.72, 0, 0, 1, 1, 0.66)}, {}});
  map.push_back({"boot", {fractions(0, 0, 0, 0.25, 1, 0.66)}, {}});
  // The sides between the axles: a door has a beam and a sill, not a crush zone; NHTSA's side stiffness
  // coefficients run at about half the front's.
  RegionMaterial doors{
      "doors", {fractions(0.25, 0, 0.1, 0.72, 0.2, 0.62), fractions(0.25, 0.8, 0.1, 0.72, 1, 0.62)}, {}};
  doors.set("crush_strength_Pa", 2.0e5);
  map.push_back(doors);
  // The greenhouse's sides: pillars are closed sections, far stiffer in bending than a flat panel.
  RegionMaterial pillars{
      "pillars", {fractions(0.2, 0, 0.62, 0.8, 0.25, 0.93), fractions(0.2, 0.75, 0.62, 0.8, 1, 0.93)}, {}};
  pillars.set("shell_bending_stiffness_N_m", 36.0);
  pillars.set("shell_yield_moment_N", 160.0);
  map.push_back(pillars);
  // The roof panel: FMVSS 216a asks it to carry 3 x the car's weight (44 kN for 1500 kg) on a 0.76 x
  // 1.83 m plate within 127 mm of crush, 32 kPa; cars rated good carry about twice that.
  RegionMaterial roof{"roof", {fractions(0.2, 0, 0.93, 0.8, 1, 1)}, {}};
  roof.set("crush_strength_Pa", 6.0e4);
  map.push_back(roof);
  // Bumpers: named for a scene to set, the crush zone's material until a low-speed test calibrates them
  // (measured: weaker crash-box columns, 2.5e5 Pa, let 60 points crush 0.50 m and 2000 points 0.72 m at
  // 56 km/h; a stiffer beam, 4 x the bending, lets a 500 km/h front through a 0.2 m wall).
  RegionMaterial bumper{"bumper", {fractions(0.95, 0, 0, 1, 1, 0.45), fractions(0, 0, 0, 0.04, 1, 0.45)}, {}};
  map.push_back(bumper);
  return map;
}

deform::Aabb placeFractions(const deform::Aabb& fractions, const deform::Aabb& bounds_m, bool reach_beyond) {
  const Eigen::Vector3d size = bounds_m.size_m();
  Eigen::Vector3d lo = fractions.min_m, hi = fractions.max_m;
  if (reach_beyond) {
    lo = Eigen::Vector3d(reach(lo.x()), reach(lo.y()), reach(lo.z()));
    hi = Eigen::Vector3d(reach(hi.x()), reach(hi.y()), reach(hi.z()));
  }
  return {bounds_m.min_m + lo.cwiseProduct(size), bounds_m.min_m + hi.cwiseProduct(size)};
}

std::vector<deform::Aabb> sedanRigidParts() {
  // The passenger cell: from the rear seat's back (0.22) to the bulkhead (0.74), its floor and roof rails
  // 8 % and 15 % inside the skin, its sides 20 % of the width in (0.36 m on the sedan: the door, its beam
  // and the B-pillar crush before the seats' cross-members do). The engine block where it stops, pushed
  // back against the bulkhead: the middle 40 % of the width, from 15 to 50 % of the height, its front at
  // 0.82 (0.86 m behind the sedan's bumper: the stroke the hull shrunk by crush_allowance_m gave).
  return {fractions(0.22, 0.2, 0.08, 0.74, 0.8, 0.85), fractions(0.74, 0.3, 0.15, 0.82, 0.7, 0.5)};
}

std::vector<deform::MaterialRegion> placeMaterialMap(const std::vector<RegionMaterial>& map,
                                                     const deform::Material& base,
                                                     const deform::Aabb& bounds_m) {
  std::vector<deform::MaterialRegion> placed;
  for (const RegionMaterial& region : map) {
    const std::string field = "vehicle.deformation.regions." + region.name;
    deform::Material material = base;
    for (const auto& [member, value] : region.values) material.*(member->member) = value;
    deform::checkMaterial(material, field);
    for (const deform::Aabb& box : region.boxes) {
      if (!((box.min_m.array() <= box.max_m.array()).all()))
        throw deform::InputError(field + ".box: its lower corner must not exceed its upper one");
      deform::MaterialRegion r;
      r.material = material;
      r.box_m = placeFractions(box, bounds_m, true);
      placed.push_back(r);
    }
  }
  return placed;
}

}  // namespace vehicle
