// Splitting a loop over [0, n) into contiguous ranges, one per thread.
#pragma once

#include <algorithm>
#include <cstdint>
#include <system_error>
#include <thread>
#include <vector>

namespace dbss::detail {

// Ranges smaller than this are not worth a thread's start-up (~20 µs; 8192
// faces are a few hundred µs of work).
inline constexpr uint32_t kMinPerThread = 8192;

// Runs fn(begin, end) over [0, n) in at most `threads` contiguous pieces of
// at least `min_piece` elements; fn must not throw.  Callers write each
// output element from exactly one piece, so the split cannot change any
// value.  If the system refuses a thread, its piece runs on this one.
template <class F>
void parallel_ranges(uint32_t n, unsigned threads, F&& fn, uint32_t min_piece = kMinPerThread) {
  threads = std::max(1u, std::min<unsigned>(threads, n / std::max(1u, min_piece)));
  if (threads <= 1) {
    fn(0u, n);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);  // may throw, but before any thread runs
  const uint32_t chunk = (n + threads - 1) / threads;
  for (unsigned i = 1; i < threads; ++i) {
    const uint32_t b = std::min(n, i * chunk), e = std::min(n, b + chunk);
    try {
      pool.emplace_back([&fn, b, e] { fn(b, e); });
    } catch (const std::system_error&) {
      fn(b, e);  // no thread to be had: same result, this thread does it
    }
  }
  fn(0u, std::min(n, chunk));
  for (auto& t : pool) t.join();
}

}  // namespace dbss::detail
