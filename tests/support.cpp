#include "support.hpp"

#include <cstdio>
#include <cstdlib>

namespace test_support {

std::optional<std::string> testMeshesDir() {
  const char* dir = std::getenv("DEFORM_TEST_MESHES");
  if (dir == nullptr || *dir == '\0') return std::nullopt;
  return std::string(dir);
}

void reportSkip(const std::string& reason) {
  std::printf("SKIPPED: %s\n", reason.c_str());
  std::fflush(stdout);
}

}  // namespace test_support
