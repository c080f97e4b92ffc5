// A clean cloud's fit made to interpolate the points around the line: the
// fitted height plus the fit's residuals at the three points of the local
// Delaunay triangle the line passes through, interpolated (barycentric) at
// the line's trace.
//
// Why: on a clean cloud the points lie on the surface, and the quadric fit
// (surface_fit.h) passes between them: over its 24 points it rounds the
// bends of a surface that is faceted at the points' scale (bench/rd_bench.md,
// twelfth session).  Advancing front, which interpolates the points, is
// exact at the points themselves.  The fit plus its interpolated residuals
// is exact at the three points and keeps the fit's curvature between them.
#pragma once

#include "dbss/encoder/point_index.h"
#include "dbss/encoder/surface_fit.h"

namespace dbss {

inline constexpr size_t kResidualPoints = 16;

// p: the odd vertex; n: its unit normal; f: the fit along that line (ok,
// blend 0).  On success t is the corrected height along n, within half the
// fit's radius of f.height.
bool residual_hit(const PointIndex& index, const double p[3], const double n[3], const SurfaceFit& f, double& t);

}  // namespace dbss
