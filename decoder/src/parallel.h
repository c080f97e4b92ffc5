// Splitting a loop over [0, n) into contiguous ranges, one per thread.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <system_error>
#include <thread>
#include <type_traits>
#include <vector>

namespace dbss::detail {

// Ranges smaller than this are not worth a thread's start-up (~20 µs; 8192
// faces are a few hundred µs of work).
inline constexpr uint32_t kMinPerThread = 8192;

// Runs fn(begin, end) over [0, n) in at most `threads` contiguous pieces of
// at least `min_piece` elements, with helper threads kept from one call to
// the next: starting and joining a thread costs 24-35 µs here, and a level
// step makes four parallel passes, so fresh threads cost a level-4 decode
// about 8%.
// Between calls the helpers spin a little (passes follow each other within
// microseconds), then sleep on a futex (std::atomic::wait).  One caller at a
// time; the destructor stops and joins the helpers.
class Workers {
 public:
  Workers() = default;
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;
  ~Workers() {
    stop_.store(true, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
    generation_.notify_all();
    for (auto& t : helpers_) t.join();
  }

  // Callers write each output element from exactly one piece, so any split
  // gives the same values.  fn must not throw; a helper the system refuses
  // means fewer pieces.
  template <class F>
  void run(uint32_t n, unsigned threads, F&& fn, uint32_t min_piece = kMinPerThread) {
    threads = std::max(1u, std::min<unsigned>(threads, n / std::max(1u, min_piece)));
    if (threads > 1) start(threads - 1);
    const unsigned pieces = std::min<unsigned>(threads, static_cast<unsigned>(helpers_.size()) + 1);
    if (pieces <= 1) {
      fn(0u, n);
      return;
    }
    const uint32_t chunk = (n + pieces - 1) / pieces;
    using Fn = std::remove_reference_t<F>;
    job_ = {[](const void* f, uint32_t b, uint32_t e) { (*static_cast<Fn*>(const_cast<void*>(f)))(b, e); },
            static_cast<const void*>(&fn), n, chunk, pieces};
    // Every helper answers every call, with a piece or without, so none is
    // still reading job_ when the next call rewrites it.
    pending_.store(static_cast<unsigned>(helpers_.size()), std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);  // publishes job_
    generation_.notify_all();
    fn(0u, std::min(n, chunk));
    for (unsigned spin = 0;; ++spin) {
      const unsigned left = pending_.load(std::memory_order_acquire);  // sees the helpers' writes
      if (left == 0) break;
      if (spin > kSpin) pending_.wait(left, std::memory_order_acquire);
      else relax();
    }
  }

 private:
  static constexpr unsigned kSpin = 1u << 12;
  // A spinning core tells the processor it is waiting.
  static void relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  struct Job {
    void (*call)(const void*, uint32_t, uint32_t);
    const void* fn;
    uint32_t n, chunk;
    unsigned pieces;
  };

  void start(unsigned helpers) {
    while (helpers_.size() < helpers) {
      const unsigned piece = static_cast<unsigned>(helpers_.size()) + 1;
      const uint32_t seen = generation_.load(std::memory_order_relaxed);
      try {
        helpers_.emplace_back([this, piece, seen] { serve(piece, seen); });
      } catch (const std::system_error&) {
        return;  // no thread to be had: fewer pieces, same results
      }
    }
  }

  void serve(unsigned piece, uint32_t seen) {
    for (;;) {
      uint32_t now;
      for (unsigned spin = 0; (now = generation_.load(std::memory_order_acquire)) == seen; ++spin)
        if (spin > kSpin) generation_.wait(seen, std::memory_order_acquire);
        else relax();
      seen = now;
      if (stop_.load(std::memory_order_relaxed)) return;
      if (piece < job_.pieces) {
        const uint32_t b = std::min(job_.n, piece * job_.chunk), e = std::min(job_.n, b + job_.chunk);
        job_.call(job_.fn, b, e);
      }
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) pending_.notify_one();
    }
  }

  std::vector<std::thread> helpers_;
  Job job_{};
  std::atomic<uint32_t> generation_{0};
  std::atomic<unsigned> pending_{0};
  std::atomic<bool> stop_{false};
};

// Runs fn(begin, end) over [0, n) in at most `threads` contiguous pieces of
// at least `min_piece` elements, on threads started for this call only (for
// callers that make one parallel pass, not many); fn must not throw.
template <class F>
void parallel_ranges(uint32_t n, unsigned threads, F&& fn, uint32_t min_piece = kMinPerThread) {
  Workers w;
  w.run(n, threads, fn, min_piece);
}

}  // namespace dbss::detail
