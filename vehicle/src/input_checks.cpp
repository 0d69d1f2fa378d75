// The shared input checks (input_checks.hpp).
#include "input_checks.hpp"

#include <deform/error.hpp>

#include <cmath>

namespace vehicle::detail {

std::string fieldMessage(std::string_view field, std::string_view rule, double value) {
  return std::string(field) + ": " + std::string(rule) + " (got " + std::to_string(value) + ")";
}

void require(bool ok, std::string_view field, std::string_view rule, double value) {
  if (!ok) throw deform::InputError(fieldMessage(field, rule, value));
}

void requirePositive(double value, std::string_view field) {
  require(std::isfinite(value) && value > 0, field, "must be finite and positive", value);
}

void requireNonNegative(double value, std::string_view field) {
  require(std::isfinite(value) && value >= 0, field, "must be finite and not negative", value);
}

void requireFinite(const Eigen::Vector3d& v, std::string_view field) {
  if (!v.allFinite()) throw deform::InputError(std::string(field) + ": must be finite");
}

void requireFinite(const Pose& pose, std::string_view field) {
  if (!pose.position_m.allFinite() || !pose.orientation.coeffs().allFinite() ||
      std::abs(pose.orientation.norm() - 1.0) > 1e-6)
    throw deform::InputError(std::string(field) + ": must be finite with a unit quaternion");
}

}  // namespace vehicle::detail
