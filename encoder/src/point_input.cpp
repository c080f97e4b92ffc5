// Whether a point set can be reconstructed at all, before any work is done.
#include "dbss/encoder/point_input.h"

#include <array>
#include <cmath>

namespace dbss {

namespace {
Status invalid(const std::string& name, const std::string& what) {
  return Status(ErrorCode::invalid_argument, name + ": " + what);
}
}  // namespace

Status check_reconstructible(const PointCloud& c, const std::string& name) {
  const size_t n = c.size();
  if (n < 4) return invalid(name, "needs at least 4 points, has " + std::to_string(n));
  // The file readers refuse such coordinates already; points handed over in
  // memory (the library, Python) are checked here: the point index squares
  // distances in float, which overflow past about 1e19.
  for (size_t i = 0; i < c.xyz.size(); ++i)
    if (!std::isfinite(c.xyz[i]) || std::abs(c.xyz[i]) > 1e15f)
      return invalid(name, "point " + std::to_string(i / 3) + " has a coordinate that is NaN, infinite or over 1e15");
  auto p = [&](size_t i) { return std::array<double, 3>{c.xyz[3 * i], c.xyz[3 * i + 1], c.xyz[3 * i + 2]}; };
  auto sub = [](std::array<double, 3> a, std::array<double, 3> b) {
    return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  };
  auto dot = [](std::array<double, 3> a, std::array<double, 3> b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto cross = [](std::array<double, 3> a, std::array<double, 3> b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  // Farthest point from p0, farthest from the line, farthest from the plane:
  // the spread in each successive direction, relative to the extent.
  const auto p0 = p(0);
  size_t i1 = 0;
  double best = 0;
  for (size_t i = 1; i < n; ++i)
    if (double d = dot(sub(p(i), p0), sub(p(i), p0)); d > best) best = d, i1 = i;
  const double extent = std::sqrt(best);
  if (extent == 0) return invalid(name, "all points are the same point");
  const auto axis = sub(p(i1), p0);
  size_t i2 = 0;
  best = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto cr = cross(axis, sub(p(i), p0));
    if (double d = dot(cr, cr); d > best) best = d, i2 = i;
  }
  if (std::sqrt(best) / dot(axis, axis) < 1e-6) return invalid(name, "all points lie on one line");
  const auto normal = cross(axis, sub(p(i2), p0));
  const double nn = std::sqrt(dot(normal, normal));
  best = 0;
  for (size_t i = 0; i < n; ++i) best = std::max(best, std::abs(dot(normal, sub(p(i), p0))) / nn);
  if (best / extent < 1e-6) return invalid(name, "all points lie on one plane; a closed surface needs volume");
  // After the shape checks, which say more about a handful of points.
  if (n < kMinReconstructPoints)
    return invalid(name, "has " + std::to_string(n) + " points; reconstructing a surface needs at least " +
                             std::to_string(kMinReconstructPoints));
  return {};
}

}  // namespace dbss
