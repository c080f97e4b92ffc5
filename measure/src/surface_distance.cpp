// Two-sided distances between points and a mesh, for error figures.
#include "dbss/measure/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace dbss {

namespace {
inline double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline void sub3(const double* a, const double* b, double* o) { o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2]; }
inline double dist2(const double* a, const double* b) {
  double d[3];
  sub3(a, b, d);
  return dot3(d, d);
}
}  // namespace

TwoSidedDistance two_sided_distance(const PointIndex& index, const TriangleMesh& mesh) {
  TwoSidedDistance out;
  const PointCloud& pc = index.points();
  if (pc.size() == 0 || mesh.triangle_count() == 0) return out;
  const TriangleTree tree(mesh);
  double sum = 0;
  for (size_t i = 0; i < pc.size(); ++i) {
    const double p[3] = {pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]};
    const double d = tree.distance(p);
    sum += d;
    out.points_to_mesh_max = std::max(out.points_to_mesh_max, d);
  }
  out.points_to_mesh_mean = sum / static_cast<double>(pc.size());

  const double spacing = std::max(point_spacing(index, 1, 0.5), 1e-12);
  double weighted = 0, area_sum = 0;
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    double c[3][3];
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) c[k][a] = mesh.positions[3 * size_t{mesh.triangles[3 * f + k]} + a];
    const double longest = std::sqrt(std::max({dist2(c[0], c[1]), dist2(c[1], c[2]), dist2(c[2], c[0])}));
    const int k = static_cast<int>(std::clamp(std::ceil(longest / spacing), 1.0, 64.0));
    double e1[3], e2[3], nrm[3];
    sub3(c[1], c[0], e1), sub3(c[2], c[0], e2);
    nrm[0] = e1[1] * e2[2] - e1[2] * e2[1], nrm[1] = e1[2] * e2[0] - e1[0] * e2[2], nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double area = 0.5 * std::sqrt(dot3(nrm, nrm));
    const size_t samples = size_t(k + 1) * size_t(k + 2) / 2;
    double tri_sum = 0;
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        const double u = double(i) / k, v = double(j) / k;
        const float q[3] = {static_cast<float>(c[0][0] + u * e1[0] + v * e2[0]),
                            static_cast<float>(c[0][1] + u * e1[1] + v * e2[1]),
                            static_cast<float>(c[0][2] + u * e1[2] + v * e2[2])};
        const float* x = &pc.xyz[3 * size_t{index.nearest(q)}];
        const double d = std::sqrt(std::pow(double{q[0]} - x[0], 2) + std::pow(double{q[1]} - x[1], 2) + std::pow(double{q[2]} - x[2], 2));
        tri_sum += d;
        out.mesh_to_points_max = std::max(out.mesh_to_points_max, d);
      }
    weighted += area * tri_sum / static_cast<double>(samples);
    area_sum += area;
  }
  out.mesh_to_points_mean = area_sum > 0 ? weighted / area_sum : 0;
  return out;
}

}  // namespace dbss
