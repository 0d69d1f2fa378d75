#pragma once
// Wall-clock timing shared by the commands that report what their parts took.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

namespace sandbox {

/// The clock every measured time is read from: steady (never set back).
using Clock = std::chrono::steady_clock;

/// Milliseconds since `start`.
inline double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Seconds since `start`.
inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The median of `v` (not empty; of an even count, the upper of the middle two).
inline double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace sandbox
