#pragma once
// The material map of a car (docs/CRASH_CALIBRATION.md, "Material map"): named regions of the body
// (bumper, bonnet, doors, pillars, roof, boot), each a set of boxes in fractions of the car's bounding
// box, with the members of the car's material it sets. deform samples the map over the skin, so a
// region is a part of the car, not a set of control points, and the map holds at every level of detail.
#include <deform/material.hpp>
#include <deform/mesh.hpp>

#include <optional>
#include <string>
#include <vector>

namespace deform {
struct MaterialRegion;
}

namespace vehicle {

/// One member of deform::Material by its scene-key name (crush_strength_Pa, ...).
struct MaterialMember {
  const char* key;
  double deform::Material::*member;
  double min, max;  ///< range a scene file may give [the member's unit]
};
/// Every member a scene or a region may set, in the order scene files document them.
const std::vector<MaterialMember>& materialMembers();

/// A named region: where it is and what it changes.
struct RegionMaterial {
  std::string name;
  /// Boxes in fractions of the car's bounding box, vehicle frame: x 0 at the rear to 1 at the front, y 0
  /// on the right to 1 on the left, z 0 at the bottom to 1 at the top. A later region wins where boxes
  /// overlap.
  std::vector<deform::Aabb> boxes;
  /// The members it sets, (member, value); the rest are the car's material.
  std::vector<std::pair<const MaterialMember*, double>> values;

  /// Sets `key` (a materialMembers() key) to `value`; false for an unknown key.
  bool set(const std::string& key, double value);
  /// The value it gives `key`, if any.
  std::optional<double> get(const std::string& key) const;
};

/// The sedan's map (scene key vehicle.deformation.material_map "sedan"; docs/CRASH_CALIBRATION.md gives
/// each value with its source): bumper, bonnet, boot, doors, pillars, roof. Placed by fractions of the
/// bounding box, it fits any car. Not yet the default: its values come from published standards and
/// ratios, not from a calibration of this model.
std::vector<RegionMaterial> sedanMaterialMap();

/// A box in fractions of the car's bounding box placed on a car whose skin spans `bounds_m`. With
/// `reach_beyond` (a region of the skin), a fraction of 0 or 1 reaches 1 % beyond the box, so the skin on
/// its faces is in; without (a rigid part), the box stays inside the car.
deform::Aabb placeFractions(const deform::Aabb& fractions, const deform::Aabb& bounds_m, bool reach_beyond);

/// The sedan's rigid parts (DeformationSettings::rigid_parts), in fractions of its bounding box, and every
/// car's default: the passenger cell (between the axles, the sills and the roof rails inside it) and the
/// engine block ahead of it (docs/CRASH_CALIBRATION.md, "Rigid parts").
std::vector<deform::Aabb> sedanRigidParts();

/// The map placed on a car whose skin spans `bounds_m` (vehicle frame): each region's boxes scaled to
/// the car (a box at a fraction 0 or 1 reaches 1 % beyond it), its material the car's with the region's
/// values set. Throws deform::InputError naming "vehicle.deformation.regions.<name>" for a bad value.
std::vector<deform::MaterialRegion> placeMaterialMap(const std::vector<RegionMaterial>& map,
                                                     const deform::Material& base,
                                                     const deform::Aabb& bounds_m);

}  // namespace vehicle
