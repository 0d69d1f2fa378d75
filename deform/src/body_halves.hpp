#pragma once
// A pass over a body in two halves (SolverParams::threads): side by side on two threads, or one after
// the other on one, with the same result. Each half writes only its own outputs and keeps its own sums,
// which the caller adds half 0 first.
#include <omp.h>

#include <cstddef>
#include <cstdint>
#include <utility>

namespace deform {

/// Whether a body's passes run on two threads: asked for, and not already inside a parallel region
/// (bodies stepped side by side, each on a thread of its own, do not nest a team each).
inline bool sweepsOnTwoThreads(uint32_t threads) {
  return threads > 1 && !omp_in_parallel();
}

/// Calls fn(0) and fn(1), on two OpenMP threads when sweepsOnTwoThreads (if the runtime gives fewer, one
/// thread takes both).
template <class Fn>
void forEachHalf(uint32_t threads, Fn&& fn) {
  if (sweepsOnTwoThreads(threads)) {
#pragma omp parallel num_threads(2)
    for (int half = omp_get_thread_num(); half < 2; half += omp_get_num_threads()) fn(half);
  } else {
    fn(0);
    fn(1);
  }
}

/// The items [begin, end) of half `half` (0 or 1) of `count`: the first count / 2, then the rest.
inline std::pair<std::size_t, std::size_t> halfOf(std::size_t count, int half) {
  return half == 0 ? std::pair<std::size_t, std::size_t>{0, count / 2}
                   : std::pair<std::size_t, std::size_t>{count / 2, count};
}

}  // namespace deform
