#include "dbss/encoder/facet_hit.h"

#include "trace_search.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace dbss {

namespace {

using V = Eigen::Vector3d;
using trace::Frame;

// Whether the points `on` (indices into d, at least 3) all lie within `tol`
// of two lines.  If they do, two of the first three share a line.
bool on_two_lines(const Frame& f, const std::array<uint8_t, kFacetPoints>& on, size_t count, double tol) {
  const auto& d = f.d;
  const auto off_line = [&](const V& a, const V& b, const V& q) {
    const V u = (b - a).normalized();
    const V r = q - a;
    return (r - r.dot(u) * u).norm() >= tol;
  };
  static constexpr size_t pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (const auto& pr : pairs) {
    const V& a = d[on[pr[0]]];
    const V& b = d[on[pr[1]]];
    if (!((b - a).norm() > tol)) continue;  // no line through them
    std::array<uint8_t, kFacetPoints> rest{};
    size_t left = 0;
    for (size_t o = 0; o < count; ++o)
      if (off_line(a, b, d[on[o]])) rest[left++] = on[o];
    if (left <= 2) return true;
    if (!((d[rest[1]] - d[rest[0]]).norm() > tol)) continue;
    bool line = true;
    for (size_t o = 2; o < left && line; ++o) line = !off_line(d[rest[0]], d[rest[1]], d[rest[o]]);
    if (line) return true;
  }
  return false;
}

// A triangle that holds the trace: a facet when its plane is confirmed by
// enough of the points, and then `hit` is the line's height on it.  Points
// on two lines do not confirm a plane: any two parallel or crossing lines
// lie on one, so on a cloud sampled on a grid (a turntable scan of a
// cylinder: rows along the axis) two neighbouring rows would make every
// chord a "facet" (facet_hit_test: 3.6e-5 from a cylinder of radius 1 at
// 300 x 96 points, against the fit's 2e-8).
bool facet_accepts(const Frame& f, size_t i, size_t j, size_t k, double t0, double radius, double& hit) {
  const auto& d = f.d;
  const V normal = (d[j] - d[i]).cross(d[k] - d[i]);
  const double len = normal.norm();
  const double cos = normal.dot(f.nz);
  if (!(len > 0) || !(std::abs(cos) > 1e-6 * len)) return false;
  const V unit = normal / len;
  std::array<uint8_t, kFacetPoints> on{};
  size_t count = 0;
  for (size_t o = 0; o < f.found; ++o)
    if (std::abs((d[o] - d[i]).dot(unit)) < kFacetFlatness * radius) on[count++] = static_cast<uint8_t>(o);
  if (static_cast<int>(count) < kFacetSupport || on_two_lines(f, on, count, kFacetFlatness * radius)) return false;
  hit = d[i].dot(unit) / unit.dot(f.nz);
  return std::abs(hit - t0) <= 0.5 * radius;
}

}  // namespace

bool facet_hit(const PointIndex& index, const double p[3], const double n[3], double t0, double radius, double& t,
               FacetSearch search) {
  Frame f;
  if (!trace::make_frame(index, p, n, t0, f)) return false;
  const auto accept = [&](size_t i, size_t j, size_t k, double& hit) { return facet_accepts(f, i, j, k, t0, radius, hit); };
  const double best_r2 = search == FacetSearch::all ? trace::search_all(f, accept, t) : trace::search_pruned(f, accept, t);
  return best_r2 < HUGE_VAL;
}

}  // namespace dbss
