#pragma once
// Helpers shared by the tests.
#include <optional>
#include <string>

namespace test_support {

/// Folder of the shared third-party meshes (DEFORM_TEST_MESHES), or nothing when unset. Tests that need
/// it call this and skip with a WARN naming the variable when it is empty.
std::optional<std::string> testMeshesDir();

}  // namespace test_support
