#include "dbss/encoder/control_rounding.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

ControlRounding round_along_surface(TriangleMesh& mesh, int bits, const std::vector<uint8_t>* fixed) {
  ControlRounding out;
  const size_t n = mesh.vertex_count();
  if (n == 0 || bits < 1 || bits > 30) return out;
  // Draco's grid, computed as Draco computes it (binary32): the per-axis
  // minimum, the largest extent as the range, (2^bits - 1) steps over it.
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = mesh.positions[a];
  for (size_t v = 0; v < n; ++v)
    for (int a = 0; a < 3; ++a)
      lo[a] = std::min(lo[a], mesh.positions[3 * v + a]), hi[a] = std::max(hi[a], mesh.positions[3 * v + a]);
  float range = 0;
  for (int a = 0; a < 3; ++a) range = std::max(range, hi[a] - lo[a]);
  if (!(range > 0)) return out;
  const int32_t top = static_cast<int32_t>((uint32_t{1} << bits) - 1);
  const float inverse = static_cast<float>(top) / range, delta = range / static_cast<float>(top);
  const auto quantize = [&](float x, int a) { return static_cast<int32_t>(std::floor((x - lo[a]) * inverse + 0.5f)); };
  const auto grid = [&](int32_t k, int a) { return static_cast<float>(k) * delta + lo[a]; };
  int32_t last[3];
  for (int a = 0; a < 3; ++a) last[a] = std::min(top, quantize(hi[a], a));
  out.grid = delta;

  // Area-weighted vertex normals.
  std::vector<V3> normal(n, V3{0, 0, 0});
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    const V3 fn = face_normal(mesh, f);
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) normal[mesh.triangles[3 * f + c]][a] += fn[a];
  }

  const double slide2 = std::pow(kRoundingSlide * delta, 2);
  double nearest_sum = 0, chosen_sum = 0;
  // Each vertex's nearest grid point, for the guard below.
  std::vector<float> nearest(3 * n);
  for (size_t v = 0; v < n; ++v) {
    float* x = &mesh.positions[3 * v];
    int32_t k0[3];
    for (int a = 0; a < 3; ++a) k0[a] = quantize(x[a], a);
    const double len = std::sqrt(dot(normal[v], normal[v]));
    const V3 nv = len > 0 ? V3{normal[v][0] / len, normal[v][1] / len, normal[v][2] / len} : V3{0, 0, 0};
    const auto offset = [&](const int32_t k[3]) {
      return V3{double{grid(k[0], 0)} - x[0], double{grid(k[1], 1)} - x[1], double{grid(k[2], 2)} - x[2]};
    };
    const double plain = std::abs(dot(offset(k0), nv));
    nearest_sum += plain;
    int32_t best[3] = {k0[0], k0[1], k0[2]};
    if (len > 0 && !(fixed && (*fixed)[v])) {
      // A small share of the slide in the cost: of two points about as near
      // the plane, the one nearer the vertex.
      const auto cost = [&](const int32_t k[3]) {
        const V3 d = offset(k);
        const double along = dot(d, nv);
        return along * along + 1e-3 * (dot(d, d) - along * along);
      };
      double best_cost = cost(k0);
      int32_t k[3];
      for (int dx = -2; dx <= 2; ++dx)
        for (int dy = -2; dy <= 2; ++dy)
          for (int dz = -2; dz <= 2; ++dz) {
            const int d[3] = {dx, dy, dz};
            bool inside = true;
            for (int a = 0; a < 3; ++a) {
              k[a] = k0[a] + d[a];
              // A vertex holding the minimum or maximum keeps its nearest
              // point on that axis: the grid's origin and range stay.
              if (k[a] < 0 || k[a] > last[a] || ((x[a] == lo[a] || x[a] == hi[a]) && k[a] != k0[a])) inside = false;
            }
            if (!inside) continue;
            const V3 o = offset(k);
            const double along = dot(o, nv);
            if (dot(o, o) - along * along > slide2) continue;
            const double c = cost(k);
            if (c < best_cost) best_cost = c, best[0] = k[0], best[1] = k[1], best[2] = k[2];
          }
      ++out.vertices;
    }
    chosen_sum += std::abs(dot(offset(best), nv));
    for (int a = 0; a < 3; ++a) nearest[3 * v + a] = grid(k0[a], a), x[a] = grid(best[a], a);
  }
  // A slide of up to 1.5 steps can put the two ends of a short edge (a QEM
  // needle) on one grid point, where plain rounding keeps them apart: such
  // ends go back to their nearest points (a zero-length edge there is what
  // plain rounding would have written anyway).
  const auto same = [&](uint32_t u, uint32_t w) {
    return mesh.positions[3 * u] == mesh.positions[3 * w] && mesh.positions[3 * u + 1] == mesh.positions[3 * w + 1] &&
           mesh.positions[3 * u + 2] == mesh.positions[3 * w + 2];
  };
  for (size_t f = 0; f < mesh.triangle_count(); ++f)
    for (int c = 0; c < 3; ++c) {
      const uint32_t u = mesh.triangles[3 * f + c], w = mesh.triangles[3 * f + (c + 1) % 3];
      if (!same(u, w)) continue;
      for (const uint32_t v : {u, w})
        for (int a = 0; a < 3; ++a) mesh.positions[3 * v + a] = nearest[3 * v + a];
      ++out.merged;
    }
  out.nearest_normal = nearest_sum / static_cast<double>(n);
  out.chosen_normal = chosen_sum / static_cast<double>(n);
  return out;
}

}  // namespace dbss
