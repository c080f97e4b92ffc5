// Two-sided mesh-to-mesh distance: area-uniform samples of each surface,
// exact distances to the other through its triangle tree.
#include "dbss/measure/mesh_distance.h"

#include <algorithm>
#include <limits>
#include <thread>
#include <vector>

#include "dbss/encoder/triangle_tree.h"
#include "dbss/measure/surface_samples.h"

namespace dbss {

namespace {

struct OneWay {
  double mean = 0, max = 0;
};

// Distances from `count` samples of `from` to the surface of `to`.  Each
// distance lands in its own slot and the sum runs in sample order, so the
// thread count never changes the result.
OneWay one_way(const TriangleMesh& from, const TriangleMesh& to, size_t count, uint32_t seed, unsigned threads) {
  const double inf = std::numeric_limits<double>::infinity();
  if (to.triangle_count() == 0) return {inf, inf};
  const std::vector<double> p = sample_surface(from, count, seed);
  const size_t n = p.size() / 3;
  if (n == 0) return {};
  const TriangleTree tree(to);
  std::vector<double> d(n);
  auto run = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) d[i] = tree.distance(&p[3 * i]);
  };
  const size_t parts = std::clamp<size_t>(threads, 1, n);
  std::vector<std::thread> workers;
  for (size_t t = 1; t < parts; ++t) workers.emplace_back(run, n * t / parts, n * (t + 1) / parts);
  run(0, n / parts);
  for (std::thread& w : workers) w.join();
  OneWay out;
  for (double x : d) out.mean += x, out.max = std::max(out.max, x);
  out.mean /= static_cast<double>(n);
  return out;
}

}  // namespace

MeshDistance mesh_distance(const TriangleMesh& a, const TriangleMesh& b, const MeshDistanceOptions& options) {
  const size_t half = std::max<size_t>(options.samples / 2, 1);
  // Different seeds per side, so a mesh compared with itself is not probed
  // at the same spots twice.
  const OneWay ab = one_way(a, b, half, options.seed, options.threads);
  const OneWay ba = one_way(b, a, half, options.seed + 1, options.threads);
  return {ab.mean, ab.max, ba.mean, ba.max};
}

}  // namespace dbss
