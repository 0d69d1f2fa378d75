#pragma once
// The checks of a value where it enters the library (DESIGN.md section 9), shared by the files that check
// world, vehicle and deformation settings: each throws deform::InputError naming the field.
#include <vehicle/pose.hpp>

#include <Eigen/Core>
#include <string>
#include <string_view>

namespace vehicle::detail {

/// "<field>: <rule> (got <value>)".
std::string fieldMessage(std::string_view field, std::string_view rule, double value);
/// Throws fieldMessage(field, rule, value) unless `ok`.
void require(bool ok, std::string_view field, std::string_view rule, double value);
/// Throws "<field>: must be finite and positive (got <value>)" unless `value` is.
void requirePositive(double value, std::string_view field);
/// Throws "<field>: must be finite and not negative (got <value>)" unless `value` is.
void requireNonNegative(double value, std::string_view field);
/// Throws "<field>: must be finite" unless every coordinate of `v` is.
void requireFinite(const Eigen::Vector3d& v, std::string_view field);
/// Throws "<field>: must be finite with a unit quaternion" unless `pose` is.
void requireFinite(const Pose& pose, std::string_view field);

}  // namespace vehicle::detail
