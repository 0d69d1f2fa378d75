#pragma once
// Helpers shared by the tests.
#include <optional>
#include <string>

namespace test_support {

/// Folder of the shared third-party meshes (DEFORM_TEST_MESHES), or nothing when unset. Tests that need
/// it call this and, when it is empty, reportSkip naming the variable and return.
std::optional<std::string> testMeshesDir();

/// Prints "SKIPPED: <reason>" on stdout. CTest reports a test whose output holds that line as skipped,
/// not passed (SKIP_REGULAR_EXPRESSION, tests/CMakeLists.txt); the test returns right after.
void reportSkip(const std::string& reason);

}  // namespace test_support
