#pragma once
// The fuzz targets' 1 s limit per input, in CPU time rather than libFuzzer's wall clock (-timeout): on a
// machine shared with other builds an input waits for a core several times as long as it computes, and a
// wall-clock second flagged inputs that took 0.3 s of CPU. An input that runs past the budget and returns
// stops the fuzzer here (a finding, its input saved like a crash); one that never returns is caught by
// tools/fuzz.sh's wall-clock -timeout.
#include <cstdio>
#include <cstdlib>
#include <ctime>

namespace fuzz_support {

constexpr double kCpuBudgetS = 1.0;  ///< CPU time one input may take [s]

inline double processCpuS() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Measures one input's CPU time from construction; aborts at destruction when it exceeded the budget.
class CpuBudget {
 public:
  CpuBudget() : started_s_(processCpuS()) {}
  CpuBudget(const CpuBudget&) = delete;
  CpuBudget& operator=(const CpuBudget&) = delete;
  ~CpuBudget() {
    const double used_s = processCpuS() - started_s_;
    if (used_s > kCpuBudgetS) {
      std::fprintf(stderr, "fuzz: this input took %.2f s of CPU time (the budget is %.1f s)\n", used_s,
                   kCpuBudgetS);
      std::abort();
    }
  }

 private:
  double started_s_;
};

}  // namespace fuzz_support
