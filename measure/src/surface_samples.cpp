// Area-uniform surface samples from a fixed seed.
#include "dbss/measure/surface_samples.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dbss {

double uniform01(std::mt19937& rng) {
  const uint64_t hi = rng() >> 5, lo = rng() >> 6;  // 27 + 26 bits
  return static_cast<double>((hi << 26) | lo) * 0x1p-53;
}

double standard_normal(std::mt19937& rng) {
  const double u = 1.0 - uniform01(rng);  // (0, 1]: the logarithm stays finite
  const double v = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
}

std::vector<double> sample_surface(const TriangleMesh& mesh, size_t count, uint32_t seed) {
  // Running sum of the triangles' areas: a uniform number times the total
  // picks a triangle by area with one binary search.
  std::vector<double> cumulative(mesh.triangle_count());
  double total = 0;
  auto corner = [&](size_t f, int k, int a) { return double{mesh.positions[3 * size_t{mesh.triangles[3 * f + k]} + a]}; };
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    double e1[3], e2[3];
    for (int a = 0; a < 3; ++a) e1[a] = corner(f, 1, a) - corner(f, 0, a), e2[a] = corner(f, 2, a) - corner(f, 0, a);
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    total += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    cumulative[f] = total;
  }
  std::vector<double> out;
  if (!(total > 0)) return out;
  out.reserve(3 * count);
  std::mt19937 rng(seed);
  for (size_t i = 0; i < count; ++i) {
    const double pick = uniform01(rng) * total;
    const size_t f = std::min<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(),
                                      cumulative.size() - 1);
    // Uniform on the triangle: the square root spreads the first coordinate
    // by the triangle's width at that height.
    const double s = std::sqrt(uniform01(rng)), t = uniform01(rng);
    const double w0 = 1.0 - s, w1 = s * (1.0 - t), w2 = s * t;
    for (int a = 0; a < 3; ++a) out.push_back(w0 * corner(f, 0, a) + w1 * corner(f, 1, a) + w2 * corner(f, 2, a));
  }
  return out;
}

}  // namespace dbss
