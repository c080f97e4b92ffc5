// Timing for the benchmarks: the best of several runs, so one run's page
// faults or a neighbour's burst do not decide a figure.
#pragma once

#include <algorithm>
#include <chrono>

namespace dbss::bench {

// Runs f at least 3 and at most 100 times, stopping once `budget` seconds
// have been spent; returns the fastest run in seconds.
template <class F>
double best_seconds(F&& f, double budget = 0.5) {
  using Clock = std::chrono::steady_clock;
  double best = 1e30, spent = 0;
  for (int i = 0; i < 100 && (i < 3 || spent < budget); ++i) {
    const auto t0 = Clock::now();
    f();
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    best = std::min(best, s);
    spent += s;
  }
  return best;
}

}  // namespace dbss::bench
