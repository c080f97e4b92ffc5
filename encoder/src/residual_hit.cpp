#include "dbss/encoder/residual_hit.h"

#include "trace_search.h"

#include <Eigen/Dense>

#include <array>
#include <cmath>

namespace dbss {

static_assert(kResidualPoints == kFacetPoints, "the residual hit searches the facet hit's frame");

bool residual_hit(const PointIndex& index, const double p[3], const double n[3], const SurfaceFit& f, double& t) {
  if (!f.ok || f.blend > 0 || !(f.radius > 0)) return false;
  const double t0 = f.height;
  trace::Frame fr;
  if (!trace::make_frame(index, p, n, t0, fr)) return false;
  const auto residual = [&](size_t i) {
    const double u = fr.x[i] / f.radius, v = fr.y[i] / f.radius;
    const double* c = f.coef;
    return fr.d[i].dot(fr.nz) - (c[0] + c[1] * u + c[2] * v + c[3] * u * u + c[4] * u * v + c[5] * v * v);
  };
  // The Delaunay triangle (in the plane normal to the line) holding the
  // trace; its barycentric coordinates as the search computes them.
  const auto accept = [&](size_t i, size_t j, size_t k, double& hit) {
    const double area = trace::doubled_area(fr, i, j, k);
    const double a = (fr.x[j] * fr.y[k] - fr.x[k] * fr.y[j]) / area, b = (fr.x[k] * fr.y[i] - fr.x[i] * fr.y[k]) / area;
    hit = t0 + a * residual(i) + b * residual(j) + (1 - a - b) * residual(k);
    return std::abs(hit - t0) <= 0.5 * f.radius;
  };
  return trace::search_pruned(fr, accept, t) < HUGE_VAL;
}

}  // namespace dbss
