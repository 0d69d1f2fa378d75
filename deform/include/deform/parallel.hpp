#pragma once
// A minimal fork-join over contiguous ranges. Each chunk writes only its own outputs, so results do
// not depend on the thread count.
#include <algorithm>
#include <thread>
#include <vector>

namespace deform {

/// `threads`, or the hardware concurrency (at least 1) for 0.
inline unsigned resolveThreads(unsigned threads) {
  if (threads != 0) return threads;
  unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : hw;
}

/// Calls fn(begin, end) over contiguous chunks of [0, count) on up to `threads` threads (0: all cores).
template <class Fn>
void parallelFor(std::size_t count, unsigned threads, Fn&& fn) {
  threads = resolveThreads(threads);
  // Below a few thousand items a thread costs more than it saves.
  std::size_t max_useful = std::max<std::size_t>(1, count / 4096);
  std::size_t workers = std::min<std::size_t>(threads, max_useful);
  if (workers <= 1) {
    fn(std::size_t{0}, count);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  std::size_t chunk = (count + workers - 1) / workers;
  for (std::size_t w = 1; w < workers; ++w) {
    std::size_t begin = std::min(count, w * chunk), end = std::min(count, begin + chunk);
    pool.emplace_back([&fn, begin, end] { fn(begin, end); });
  }
  fn(std::size_t{0}, std::min(count, chunk));
  for (auto& t : pool) t.join();
}

}  // namespace deform
