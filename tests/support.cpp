#include "support.hpp"

#include <cstdlib>

namespace test_support {

std::optional<std::string> testMeshesDir() {
  const char* dir = std::getenv("DEFORM_TEST_MESHES");
  if (dir == nullptr || *dir == '\0') return std::nullopt;
  return std::string(dir);
}

}  // namespace test_support
