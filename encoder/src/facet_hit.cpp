#include "dbss/encoder/facet_hit.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

namespace dbss {

bool facet_hit(const PointIndex& index, const double p[3], const double n[3], double t0, double radius, double& t) {
  const PointCloud& pc = index.points();
  const float foot[3] = {static_cast<float>(p[0] + t0 * n[0]), static_cast<float>(p[1] + t0 * n[1]),
                         static_cast<float>(p[2] + t0 * n[2])};
  std::array<uint32_t, kFacetPoints> near{};
  std::array<float, kFacetPoints> dist2{};
  const size_t found = index.nearest_k(foot, kFacetPoints, near.data(), dist2.data());
  if (found < 3) return false;
  using V = Eigen::Vector3d;
  const V origin(p[0], p[1], p[2]), nz(n[0], n[1], n[2]);
  const V helper = std::abs(nz.x()) < 0.6 ? V::UnitX() : V::UnitY();
  const V e1 = nz.cross(helper).normalized(), e2 = nz.cross(e1);
  // The points relative to p; (x, y) in the plane normal to the line, whose
  // trace there is the origin.
  std::array<V, kFacetPoints> d;
  std::array<double, kFacetPoints> x{}, y{};
  for (size_t i = 0; i < found; ++i) {
    d[i] = V(pc.xyz[3 * near[i]], pc.xyz[3 * near[i] + 1], pc.xyz[3 * near[i] + 2]) - origin;
    x[i] = d[i].dot(e1), y[i] = d[i].dot(e2);
  }
  double best_r2 = HUGE_VAL;
  for (size_t i = 0; i < found; ++i)
    for (size_t j = i + 1; j < found; ++j)
      for (size_t k = j + 1; k < found; ++k) {
        // The line's trace inside the projected triangle (cheapest test first).
        const double area = (x[j] - x[i]) * (y[k] - y[i]) - (x[k] - x[i]) * (y[j] - y[i]);
        if (std::abs(area) < 1e-30) continue;
        const double a = (x[j] * y[k] - x[k] * y[j]) / area, b = (x[k] * y[i] - x[i] * y[k]) / area;
        if (a < 0 || b < 0 || a + b > 1) continue;
        // Delaunay: no other of the points inside its projected circumcircle
        // (the triangle advancing front or any interpolating mesh would pick).
        const double a2 = x[i] * x[i] + y[i] * y[i], b2 = x[j] * x[j] + y[j] * y[j], c2 = x[k] * x[k] + y[k] * y[k];
        const double den = 2 * area;
        const double ux = (a2 * (y[j] - y[k]) + b2 * (y[k] - y[i]) + c2 * (y[i] - y[j])) / den;
        const double uy = (a2 * (x[k] - x[j]) + b2 * (x[i] - x[k]) + c2 * (x[j] - x[i])) / den;
        const double r2 = (x[i] - ux) * (x[i] - ux) + (y[i] - uy) * (y[i] - uy);
        if (!(r2 < best_r2)) continue;
        bool empty = true;
        for (size_t o = 0; o < found && empty; ++o)
          if (o != i && o != j && o != k && (x[o] - ux) * (x[o] - ux) + (y[o] - uy) * (y[o] - uy) < r2 * (1 - 1e-9)) empty = false;
        if (!empty) continue;
        // A facet: enough of the points on its plane.
        const V normal = (d[j] - d[i]).cross(d[k] - d[i]);
        const double len = normal.norm();
        const double cos = normal.dot(nz);
        if (!(len > 0) || !(std::abs(cos) > 1e-6 * len)) continue;
        const V unit = normal / len;
        int on = 0;
        for (size_t o = 0; o < found; ++o) on += std::abs((d[o] - d[i]).dot(unit)) < kFacetFlatness * radius;
        if (on < kFacetSupport) continue;
        const double hit = d[i].dot(unit) / unit.dot(nz);
        if (!(std::abs(hit - t0) <= 0.5 * radius)) continue;
        best_r2 = r2;
        t = hit;
      }
  return best_r2 < HUGE_VAL;
}

}  // namespace dbss
