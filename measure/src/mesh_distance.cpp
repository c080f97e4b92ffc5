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

// Distances from the points `p` (3 each) to the surface `tree` holds.  Each
// distance lands in its own slot and the sum runs in sample order, so the
// thread count never changes the result.
OneWay one_way(const std::vector<double>& p, const TriangleTree& tree, unsigned threads) {
  const size_t n = p.size() / 3;
  if (n == 0) return {};
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

size_t half_samples(const MeshDistanceOptions& o) { return std::max<size_t>(o.samples / 2, 1); }

}  // namespace

// Different seeds per side, so a mesh compared with itself is not probed at
// the same spots twice: a's samples take `seed`, b's `seed + 1`.
MeshDistanceTo::MeshDistanceTo(const TriangleMesh& b, const MeshDistanceOptions& options)
    : options_(options), b_triangles_(b.triangle_count()), tree_(b),
      samples_(sample_surface(b, half_samples(options), options.seed + 1)) {}

MeshDistance MeshDistanceTo::from(const TriangleMesh& a) const {
  const double inf = std::numeric_limits<double>::infinity();
  OneWay ab{inf, inf}, ba{inf, inf};
  if (b_triangles_ > 0) ab = one_way(sample_surface(a, half_samples(options_), options_.seed), tree_, options_.threads);
  if (a.triangle_count() > 0) ba = one_way(samples_, TriangleTree(a), options_.threads);
  return {ab.mean, ab.max, ba.mean, ba.max};
}

MeshDistance mesh_distance(const TriangleMesh& a, const TriangleMesh& b, const MeshDistanceOptions& options) {
  return MeshDistanceTo(b, options).from(a);
}

}  // namespace dbss
