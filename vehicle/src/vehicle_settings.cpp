// Wheel layouts from a model's parts or its bounding box, and the settings check.
#include <vehicle/vehicle_settings.hpp>

#include <deform/error.hpp>

#include "input_checks.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace vehicle {
namespace {

constexpr double kFrontBrakeShare = 0.55;

/// Front wheels steer and brake harder; rear wheels drive and carry the handbrake.
void assignRoles(std::vector<WheelSettings>& wheels, double total_brake_Nm) {
  if (wheels.empty()) return;
  double front_x = -1e300, rear_x = 1e300;
  for (const auto& w : wheels) {
    front_x = std::max(front_x, w.centre_m.x());
    rear_x = std::min(rear_x, w.centre_m.x());
  }
  const double middle = 0.5 * (front_x + rear_x);
  std::size_t fronts = 0;
  for (const auto& w : wheels) fronts += w.centre_m.x() > middle ? 1 : 0;
  const std::size_t rears = wheels.size() - fronts;
  for (auto& w : wheels) {
    const bool front = w.centre_m.x() > middle;
    w.driven = !front;
    w.handbrake = !front;
    w.brake_torque_Nm =
        front
            ? kFrontBrakeShare * total_brake_Nm / static_cast<double>(std::max<std::size_t>(1, fronts))
            : (1 - kFrontBrakeShare) * total_brake_Nm / static_cast<double>(std::max<std::size_t>(1, rears));
  }
}

// Total brake torque of the default car: four wheels that can each lock at 1 g with load transfer.
constexpr double kTotalBrakeTorque_Nm = 4 * 2500.0;

}  // namespace

std::vector<WheelSettings> wheelsFromParts(const std::vector<deform::WheelPart>& parts) {
  std::vector<WheelSettings> wheels;
  for (const auto& part : parts) {
    WheelSettings w;
    w.centre_m = part.centre_m;
    w.radius_m = part.radius_m;
    w.width_m = part.width_m;
    w.steered = part.steered;
    wheels.push_back(w);
  }
  const bool any_steered = std::any_of(parts.begin(), parts.end(), [](const auto& p) { return p.steered; });
  assignRoles(wheels, kTotalBrakeTorque_Nm);
  if (!any_steered) {
    for (auto& w : wheels) w.steered = !w.driven;
  } else {
    for (std::size_t i = 0; i < wheels.size(); ++i) wheels[i].steered = parts[i].steered;
  }
  return wheels;
}

std::vector<WheelSettings> wheelsFromBoundingBox(const deform::Aabb& box) {
  const Eigen::Vector3d size = box.size_m(), middle = 0.5 * (box.min_m + box.max_m);
  const double radius = std::min(0.32, 0.22 * size.z());
  const double half_wheelbase = 0.29 * size.x(), half_track = 0.425 * size.y();
  const double hub_z = box.min_m.z() - 0.5 * radius;
  std::vector<WheelSettings> wheels;
  for (double side : {1.0, -1.0}) {
    for (double end : {1.0, -1.0}) {
      WheelSettings w;
      w.centre_m = {middle.x() + end * half_wheelbase, middle.y() + side * half_track, hub_z};
      w.radius_m = radius;
      w.width_m = std::min(0.22, 0.12 * size.y());
      w.steered = end > 0;
      wheels.push_back(w);
    }
  }
  assignRoles(wheels, kTotalBrakeTorque_Nm);
  return wheels;
}

std::vector<WheelSettings> wheelsFromModel(const VehicleSettings& settings,
                                           const deform::VehicleModel& model) {
  if (!settings.wheels.empty()) return settings.wheels;
  if (!model.wheels.empty()) return wheelsFromParts(model.wheels);
  return wheelsFromBoundingBox(deform::boundingBox(model.body));
}

VehicleSettings settingsForMass(const VehicleSettings& settings, double mass_kg) {
  detail::requirePositive(mass_kg, "settingsForMass: mass_kg");
  VehicleSettings out = settings;
  const double ratio = mass_kg / settings.mass_kg;
  out.mass_kg = mass_kg;
  out.engine_torque_Nm *= ratio;
  out.max_power_W *= ratio;
  out.handbrake_torque_Nm *= ratio;
  out.drag_area_m2 *= ratio;
  for (auto& w : out.wheels) {
    w.spring_N_per_m *= ratio;
    w.damper_N_s_per_m *= ratio;
    w.brake_torque_Nm *= ratio;
    w.inertia_kg_m2 *= ratio;
  }
  return out;
}

void checkVehicleSettings(const VehicleSettings& s, const char* source_c) {
  const std::string source = source_c ? source_c : "vehicle";
  const std::string where = source + ": ";  // a field's name in messages follows it
  detail::requirePositive(s.mass_kg, where + "mass_kg");
  if (!s.centre_of_mass_offset_m.allFinite())
    throw deform::InputError(source + ": centre_of_mass_offset_m must be finite");
  for (int i = 0; i < 3; ++i) detail::requirePositive(s.box_size_m[i], where + "box_size_m");
  detail::requirePositive(s.tyre.friction_coefficient, where + "tyre.friction_coefficient");
  detail::requirePositive(s.tyre.longitudinal_stiffness_per_load,
                          where + "tyre.longitudinal_stiffness_per_load");
  detail::requirePositive(s.tyre.cornering_stiffness_per_load, where + "tyre.cornering_stiffness_per_load");
  detail::requirePositive(s.tyre.longitudinal_relaxation_m, where + "tyre.longitudinal_relaxation_m");
  detail::requirePositive(s.tyre.lateral_relaxation_m, where + "tyre.lateral_relaxation_m");
  detail::requireNonNegative(s.tyre.low_speed_damping_ratio, where + "tyre.low_speed_damping_ratio");
  detail::requirePositive(s.tyre.low_speed_blend_mps, where + "tyre.low_speed_blend_mps");
  detail::requireNonNegative(s.tyre.rolling_resistance, where + "tyre.rolling_resistance");
  detail::requireNonNegative(s.max_steer_rad, where + "max_steer_rad");
  if (!(s.max_steer_rad < 1.4))
    throw deform::InputError(source + ": max_steer_rad must be below 1.4 rad (80 deg)");
  detail::requirePositive(s.steer_rate_rad_s, where + "steer_rate_rad_s");
  if (!(s.ackermann >= 0 && s.ackermann <= 1))
    throw deform::InputError(source + ": ackermann must be in [0, 1]");
  detail::requireNonNegative(s.engine_torque_Nm, where + "engine_torque_Nm");
  detail::requirePositive(s.gear_ratio, where + "gear_ratio");
  detail::requirePositive(s.max_power_W, where + "max_power_W");
  detail::requireNonNegative(s.handbrake_torque_Nm, where + "handbrake_torque_Nm");
  detail::requireNonNegative(s.drag_area_m2, where + "drag_area_m2");
  detail::requireNonNegative(s.air_density_kg_m3, where + "air_density_kg_m3");
  detail::requireNonNegative(s.body_friction, where + "body_friction");
  for (std::size_t i = 0; i < s.wheels.size(); ++i) {
    const auto& w = s.wheels[i];
    const std::string field = "wheels[" + std::to_string(i) + "].";
    if (!w.centre_m.allFinite()) throw deform::InputError(source + ": " + field + "centre_m must be finite");
    detail::requirePositive(w.radius_m, where + field + "radius_m");
    detail::requirePositive(w.width_m, where + field + "width_m");
    detail::requirePositive(w.inertia_kg_m2, where + field + "inertia_kg_m2");
    detail::requireNonNegative(w.brake_torque_Nm, where + field + "brake_torque_Nm");
    detail::requirePositive(w.spring_N_per_m, where + field + "spring_N_per_m");
    detail::requireNonNegative(w.damper_N_s_per_m, where + field + "damper_N_s_per_m");
    detail::requirePositive(w.suspension_length_m, where + field + "suspension_length_m");
    detail::requirePositive(w.max_compression_m, where + field + "max_compression_m");
  }
  if (!s.wheels.empty() && s.wheels.size() < 3)
    throw deform::InputError(source + ": wheels: a car needs at least 3 (got " +
                             std::to_string(s.wheels.size()) + ")");
}

}  // namespace vehicle
