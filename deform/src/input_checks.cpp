// The shared input checks (input_checks.hpp).
#include "input_checks.hpp"

#include <deform/error.hpp>

#include <cmath>

namespace deform::detail {

void requireFinite(const Eigen::Vector3d& v, const std::string& field) {
  if (!v.allFinite()) throw InputError(field + ": not finite");
}

void requireNonNegative(double value, const std::string& field) {
  if (!std::isfinite(value) || value < 0)
    throw InputError(field + ": must be finite and >= 0 (got " + std::to_string(value) + ")");
}

void requirePositive(double value, const std::string& field) {
  if (!std::isfinite(value) || value <= 0)
    throw InputError(field + ": must be finite and > 0 (got " + std::to_string(value) + ")");
}

}  // namespace deform::detail
