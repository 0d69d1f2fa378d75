#pragma once
// This process's resident memory, for bench memory and the stress suite's repeated impacts.
#include <unistd.h>

#include <cstdio>

namespace sandbox {

/// Resident set now [bytes] (/proc/self/statm), 0 when it cannot be read.
inline double residentBytes() {
  long pages = 0, resident = 0;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

}  // namespace sandbox
