#pragma once
// The checks of a value where it enters the library (DESIGN.md section 9), shared by the files that check
// settings and shapes: each throws InputError naming the field.
#include <Eigen/Core>
#include <string>

namespace deform::detail {

/// Throws "<field>: not finite" unless every coordinate of `v` is finite.
void requireFinite(const Eigen::Vector3d& v, const std::string& field);
/// Throws "<field>: must be finite and >= 0 (got <value>)" unless `value` is finite and not negative.
void requireNonNegative(double value, const std::string& field);
/// Throws "<field>: must be finite and > 0 (got <value>)" unless `value` is finite and positive.
void requirePositive(double value, const std::string& field);

}  // namespace deform::detail
