// Per-element passes over the points split across threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <future>
#include <system_error>
#include <vector>

namespace dbss::detail {

// Runs body(from, to) over [0, n) in at most `threads` contiguous pieces of
// about 10,000 elements or more, the first on the calling thread.  Callers
// write each output element from one piece only, so the result is the same
// on any number of threads.  A thread the system refuses runs its piece
// here instead.
template <class Body>
void split_ranges(size_t n, unsigned threads, const Body& body) {
  const unsigned pieces = std::max(1u, std::min<unsigned>(threads, static_cast<unsigned>(n / 10000 + 1)));
  std::vector<std::future<void>> helpers;
  for (unsigned t = 1; t < pieces; ++t) {
    try {
      helpers.push_back(std::async(std::launch::async, body, n * t / pieces, n * (t + 1) / pieces));
    } catch (const std::system_error&) {
      body(n * t / pieces, n * (t + 1) / pieces);
    }
  }
  body(size_t{0}, n / pieces);
  for (auto& h : helpers) h.get();
}

}  // namespace dbss::detail
