// The local Delaunay triangle of a clean cloud's points that the sampling
// line passes through: the search the facet hit (facet_hit.h) and the
// residual hit (residual_hit.h) share.  Each passes its own acceptance
// test; the triangle taken is the accepted Delaunay triangle holding the
// line's trace with the smallest circumcircle.  Private to the encoder.
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "dbss/encoder/facet_hit.h"
#include "dbss/encoder/point_index.h"

namespace dbss::trace {

using V = Eigen::Vector3d;

// search_pruned's margin for the emptiness step, relative to m^2 + 4 R^2:
// four orders of magnitude above what it must cover (1e-9 + 1e-10).
inline constexpr double kLiftSlack = 1e-6;
static_assert(kFacetPoints < 32, "the pruned search keeps the points in 32-bit masks (1u << n with n < 32)");

// The points nearest the foot, relative to p, and their coordinates (x, y)
// in the plane normal to the line, whose trace there is the origin.
struct Frame {
  size_t found = 0;
  V nz;
  std::array<V, kFacetPoints> d;
  std::array<double, kFacetPoints> x{}, y{}, z{};  // z = x^2 + y^2
};

// The kFacetPoints points nearest p + t0 n, in f; false with fewer than 3.
// (e1, e2) is surface_fit's fit_frame, so the residual hit's (x, y) over
// the fit's radius are the fit's (u, v).
inline bool make_frame(const PointIndex& index, const double p[3], const double n[3], double t0, Frame& f) {
  const PointCloud& pc = index.points();
  const float foot[3] = {static_cast<float>(p[0] + t0 * n[0]), static_cast<float>(p[1] + t0 * n[1]),
                         static_cast<float>(p[2] + t0 * n[2])};
  std::array<uint32_t, kFacetPoints> near{};
  std::array<float, kFacetPoints> dist2{};
  f.found = index.nearest_k(foot, kFacetPoints, near.data(), dist2.data());
  if (f.found < 3) return false;
  const V origin(p[0], p[1], p[2]);
  f.nz = V(n[0], n[1], n[2]);
  const V helper = std::abs(f.nz.x()) < 0.6 ? V::UnitX() : V::UnitY();
  const V e1 = f.nz.cross(helper).normalized(), e2 = f.nz.cross(e1);
  for (size_t i = 0; i < f.found; ++i) {
    f.d[i] = V(pc.xyz[3 * near[i]], pc.xyz[3 * near[i] + 1], pc.xyz[3 * near[i] + 2]) - origin;
    f.x[i] = f.d[i].dot(e1), f.y[i] = f.d[i].dot(e2);
    f.z[i] = f.x[i] * f.x[i] + f.y[i] * f.y[i];
  }
  return true;
}

// Triangle (i, j, k) holds the trace (its doubled signed area `area`):
// taken when it is Delaunay (no other of the points inside its projected
// circumcircle: the triangle advancing front or any interpolating mesh
// would pick), a facet, and its circumcircle smaller than the best so far.
template <class Accept>
void try_triangle(const Frame& f, size_t i, size_t j, size_t k, double area, const Accept& accept, double& best_r2,
                  double& t) {
  const auto& x = f.x;
  const auto& y = f.y;
  const double a2 = f.z[i], b2 = f.z[j], c2 = f.z[k];
  const double den = 2 * area;
  const double ux = (a2 * (y[j] - y[k]) + b2 * (y[k] - y[i]) + c2 * (y[i] - y[j])) / den;
  const double uy = (a2 * (x[k] - x[j]) + b2 * (x[i] - x[k]) + c2 * (x[j] - x[i])) / den;
  const double r2 = (x[i] - ux) * (x[i] - ux) + (y[i] - uy) * (y[i] - uy);
  if (!(r2 < best_r2)) return;
  for (size_t o = 0; o < f.found; ++o)
    if (o != i && o != j && o != k && (x[o] - ux) * (x[o] - ux) + (y[o] - uy) * (y[o] - uy) < r2 * (1 - 1e-9)) return;
  double hit = 0;
  if (!accept(i, j, k, hit)) return;
  best_r2 = r2;
  t = hit;
}

// The doubled signed area of (i, j, k) in the plane, as both searches
// compute it.
inline double doubled_area(const Frame& f, size_t i, size_t j, size_t k) {
  const auto& x = f.x;
  const auto& y = f.y;
  return (x[j] - x[i]) * (y[k] - y[i]) - (x[k] - x[i]) * (y[j] - y[i]);
}

// Every triangle of the points (C(16, 3) = 560), the reference the pruned
// search must match.
template <class Accept>
double search_all(const Frame& f, const Accept& accept, double& t) {
  const auto& x = f.x;
  const auto& y = f.y;
  double best_r2 = HUGE_VAL;
  for (size_t i = 0; i < f.found; ++i)
    for (size_t j = i + 1; j < f.found; ++j)
      for (size_t k = j + 1; k < f.found; ++k) {
        const double area = doubled_area(f, i, j, k);
        if (std::abs(area) < 1e-30) continue;
        const double a = (x[j] * y[k] - x[k] * y[j]) / area, b = (x[k] * y[i] - x[i] * y[k]) / area;
        if (a < 0 || b < 0 || a + b > 1) continue;
        try_triangle(f, i, j, k, area, accept, best_r2, t);
      }
  return best_r2;
}

// The same triangles, in the same order and with the same arithmetic, but
// only those that can pass: on a smooth clean cloud the exhaustive search
// ran for every fitted sample and never took a facet (kitten: 560 triangles
// per line, a third of them holding the trace, one of those Delaunay; a
// third of the whole encode's CPU).  Two steps skip triangles that provably
// fail the tests above; rounding is bounded generously, and every margin
// below errs towards testing a triangle in full.
//
// 1. Containment, by the signs of the numerators.  a = cross[j][k] / area
//    and b = cross[k][i] / area are both >= 0 only if the two numerators
//    share a sign (kept when either is within `side` of 0: no quotient of
//    a larger one by an area under 8 m^2 underflows to 0).  With that sign
//    s and area of sign s, a + b rounds to at least (cross[j][k] +
//    cross[k][i]) / area (1 - 2u), and the exact area is the sum of the
//    three exact numerators; so a + b > 1 whenever cross[i][j] has sign -s
//    beyond the rounding of the three numerators (4u m^2 each) and of the
//    area (32u m^2) plus 2u (|a| + |b|) area: 52u m^2 < `side`.
// 2. Emptiness, by the lifting map: a circle's points lifted to the
//    paraboloid z = x^2 + y^2 lie on a plane, and a point is inside the
//    circle when it lies below that plane.  A Delaunay triangle's plane is
//    below every lifted point (within the emptiness test's 1e-9 r^2), so at
//    the trace it is below every other containing triangle's plane, whose
//    height there is a convex combination of lifted points.  A triangle
//    whose height at the trace exceeds the lowest by more than kLiftSlack
//    (m^2 + 4 R^2) is not empty: the test's tolerance is 1e-9 r^2, and the
//    rounding of barycentric coordinates and circumcentres, for triangles
//    whose area is at least `conditioned` (R under 1e4 m), is below 1e-10
//    (m^2 + R^2).  Thinner triangles are tested in full, and only the
//    others give the lowest height.
// Checked against search_all on random, grid and cocircular clouds
// (facet_hit_test) and by byte-identical files (bench/rd_bench.md,
// fourteenth session).
template <class Accept>
double search_pruned(const Frame& f, const Accept& accept, double& t) {
  const auto& x = f.x;
  const auto& y = f.y;
  const size_t n = f.found;
  double m = 0;
  for (size_t i = 0; i < n; ++i) m = std::max({m, std::abs(x[i]), std::abs(y[i])});
  const double m2 = m * m;
  // Outside this range the error bounds below may underflow or overflow.
  if (!(m2 > 1e-200 && m2 < 1e200)) return search_all(f, accept, t);
  // Step 1: cross[p][q], computed as the containment test computes its
  // numerators (x[p] y[q] - x[q] y[p]; the other order is its negation,
  // exactly, as rounding to nearest is symmetric, and 0 - c gives +0 where
  // the difference is 0); its sign counts only beyond `side`.  Both this
  // and the containment test rely on the build's -ffp-contract=off
  // (CMakeLists.txt): a fused multiply-add would round the two differently.
  const double side = 1e-13 * m2;
  std::array<std::array<double, kFacetPoints>, kFacetPoints> cross;
  std::array<uint32_t, kFacetPoints> pos{}, neg{};
  for (size_t p = 0; p < n; ++p)
    for (size_t q = p + 1; q < n; ++q) {
      const double c = x[p] * y[q] - x[q] * y[p];
      cross[p][q] = c;
      cross[q][p] = 0.0 - c;
      const uint32_t above = c > side, below = c < -side;
      pos[p] |= above << q, neg[p] |= below << q;
      pos[q] |= below << p, neg[q] |= above << p;
    }
  // The containing triangles, with the lifted height of their plane at the
  // trace (the paraboloid z = x^2 + y^2 interpolated there).
  struct Held {
    uint8_t i, j, k;
    double area, lift;
  };
  std::array<Held, kFacetPoints * (kFacetPoints - 1) * (kFacetPoints - 2) / 6> held;
  size_t count = 0;
  double lowest = HUGE_VAL;
  const double conditioned = 1e-3 * m2;
  const uint32_t all = (1u << n) - 1;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      // (The sign of cross[k][i] is the opposite of cross[i][k]'s.)
      uint32_t out = (pos[j] & pos[i]) | (neg[j] & neg[i]);
      if (cross[i][j] < -side) out |= pos[j] & neg[i];
      if (cross[i][j] > side) out |= neg[j] & pos[i];
      for (uint32_t ks = all & ~((2u << j) - 1) & ~out; ks != 0; ks &= ks - 1) {
        const size_t k = static_cast<size_t>(std::countr_zero(ks));
        const double area = doubled_area(f, i, j, k);
        if (std::abs(area) < 1e-30) continue;
        const double a = cross[j][k] / area, b = cross[k][i] / area;
        if (a < 0 || b < 0 || a + b > 1) continue;
        const double lift = a * f.z[i] + b * f.z[j] + (1 - a - b) * f.z[k];
        held[count++] = {static_cast<uint8_t>(i), static_cast<uint8_t>(j), static_cast<uint8_t>(k), area, lift};
        if (std::abs(area) >= conditioned) lowest = std::min(lowest, lift);
      }
    }
  // Step 2: only triangles whose lifted plane at the trace is about the
  // lowest (4 R^2 = the product of the squared sides over area^2).
  const auto len2 = [&](size_t p, size_t q) { return (x[p] - x[q]) * (x[p] - x[q]) + (y[p] - y[q]) * (y[p] - y[q]); };
  double best_r2 = HUGE_VAL;
  for (size_t c = 0; c < count; ++c) {
    const Held& h = held[c];
    if (std::abs(h.area) >= conditioned) {
      const double a2 = h.area * h.area;
      const double sides = len2(h.i, h.j) * len2(h.j, h.k) * len2(h.k, h.i);
      if ((h.lift - lowest) * a2 > kLiftSlack * (m2 * a2 + sides)) continue;
    }
    try_triangle(f, h.i, h.j, h.k, h.area, accept, best_r2, t);
  }
  return best_r2;
}

}  // namespace dbss::trace
