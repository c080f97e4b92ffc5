#include "dbss/encoder/residual_hit.h"

#include <Eigen/Dense>

#include <array>
#include <cmath>

namespace dbss {

bool residual_hit(const PointIndex& index, const double p[3], const double n[3], const SurfaceFit& f, double& t) {
  if (!f.ok || f.blend > 0 || !(f.radius > 0)) return false;
  const PointCloud& pc = index.points();
  const double t0 = f.height;
  const float foot[3] = {static_cast<float>(p[0] + t0 * n[0]), static_cast<float>(p[1] + t0 * n[1]),
                         static_cast<float>(p[2] + t0 * n[2])};
  std::array<uint32_t, kResidualPoints> near{};
  std::array<float, kResidualPoints> dist2{};
  const size_t found = index.nearest_k(foot, kResidualPoints, near.data(), dist2.data());
  if (found < 3) return false;
  using V = Eigen::Vector3d;
  double a1[3], a2[3];
  fit_frame(n, a1, a2);
  const V origin(p[0], p[1], p[2]), nz(n[0], n[1], n[2]), e1(a1[0], a1[1], a1[2]), e2(a2[0], a2[1], a2[2]);
  std::array<double, kResidualPoints> x{}, y{}, h{};
  for (size_t i = 0; i < found; ++i) {
    const V d = V(pc.xyz[3 * near[i]], pc.xyz[3 * near[i] + 1], pc.xyz[3 * near[i] + 2]) - origin;
    x[i] = d.dot(e1), y[i] = d.dot(e2), h[i] = d.dot(nz);
  }
  const auto residual = [&](size_t i) {
    const double u = x[i] / f.radius, v = y[i] / f.radius;
    const double* c = f.coef;
    return h[i] - (c[0] + c[1] * u + c[2] * v + c[3] * u * u + c[4] * u * v + c[5] * v * v);
  };
  // The Delaunay triangle (in the plane normal to the line) holding the trace.
  double best_r2 = HUGE_VAL;
  for (size_t i = 0; i < found; ++i)
    for (size_t j = i + 1; j < found; ++j)
      for (size_t k = j + 1; k < found; ++k) {
        const double area = (x[j] - x[i]) * (y[k] - y[i]) - (x[k] - x[i]) * (y[j] - y[i]);
        if (std::abs(area) < 1e-30) continue;
        const double a = (x[j] * y[k] - x[k] * y[j]) / area, b = (x[k] * y[i] - x[i] * y[k]) / area;
        if (a < 0 || b < 0 || a + b > 1) continue;
        const double q2 = x[i] * x[i] + y[i] * y[i], r2j = x[j] * x[j] + y[j] * y[j], c2 = x[k] * x[k] + y[k] * y[k];
        const double den = 2 * area;
        const double ux = (q2 * (y[j] - y[k]) + r2j * (y[k] - y[i]) + c2 * (y[i] - y[j])) / den;
        const double uy = (q2 * (x[k] - x[j]) + r2j * (x[i] - x[k]) + c2 * (x[j] - x[i])) / den;
        const double r2 = (x[i] - ux) * (x[i] - ux) + (y[i] - uy) * (y[i] - uy);
        if (!(r2 < best_r2)) continue;
        bool empty = true;
        for (size_t o = 0; o < found && empty; ++o)
          if (o != i && o != j && o != k && (x[o] - ux) * (x[o] - ux) + (y[o] - uy) * (y[o] - uy) < r2 * (1 - 1e-9)) empty = false;
        if (!empty) continue;
        const double hit = t0 + a * residual(i) + b * residual(j) + (1 - a - b) * residual(k);
        if (!(std::abs(hit - t0) <= 0.5 * f.radius)) continue;
        best_r2 = r2;
        t = hit;
      }
  return best_r2 < HUGE_VAL;
}

}  // namespace dbss
