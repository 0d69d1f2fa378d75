#pragma once
// Errors raised where input enters the library (DESIGN.md section 9). Inside the solver there are
// numeric guards instead; programming errors are asserts.
#include <stdexcept>
#include <string>

namespace deform {

/// Bad input from a user: a file, a field or a value. The message names the source and the problem,
/// e.g. "car.glb: no triangles" or "--control-points: must be at least 4 (got 2)".
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace deform
