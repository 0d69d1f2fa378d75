#pragma once
// Checks on paths that come from users. std::filesystem's throwing forms raise filesystem_error on a
// path the system cannot even look at (a name over 255 bytes, a loop of links, no permission), which
// escaped as an internal failure; these answer "no" instead, so that the caller's message names the path.
#include <filesystem>
#include <system_error>

namespace deform {

/// True when `path` names a regular file (after links); false when it does not or cannot be looked at.
inline bool isRegularFile(const std::filesystem::path& path) noexcept {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) && !ec;
}

/// True when `path` names a folder (after links); false when it does not or cannot be looked at.
inline bool isDirectory(const std::filesystem::path& path) noexcept {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec) && !ec;
}

/// True when something exists at `path`; false when nothing does or it cannot be looked at.
inline bool pathExists(const std::filesystem::path& path) noexcept {
  std::error_code ec;
  return std::filesystem::exists(path, ec) && !ec;
}

}  // namespace deform
