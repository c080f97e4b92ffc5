// Holes cut in a closed mesh for the benches (lod_bench --cut-holes,
// scale_bench --mesh MESH:STEPS:HOLES): one definition, so the two benches
// cut the same holes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"

namespace dbss::bench {

// The bounding box's diagonal of a mesh's vertices.
inline double diagonal(const TriangleMesh& m) {
  if (m.vertex_count() == 0) return 0;
  float lo[3] = {m.positions[0], m.positions[1], m.positions[2]}, hi[3] = {lo[0], lo[1], lo[2]};
  for (size_t i = 0; i < m.vertex_count(); ++i)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], m.positions[3 * i + a]), hi[a] = std::max(hi[a], m.positions[3 * i + a]);
  double d = 0;
  for (int a = 0; a < 3; ++a) d += (double(hi[a]) - lo[a]) * (double(hi[a]) - lo[a]);
  return std::sqrt(d);
}

// `count` holes: the triangles with a corner within `radius` of the
// diagonal of vertices spread evenly through the vertex list, removed.
inline TriangleMesh cut_holes(const TriangleMesh& m, uint32_t count, double radius) {
  const double r2 = std::pow(radius * diagonal(m), 2);
  std::vector<uint8_t> gone(m.vertex_count(), 0);
  for (uint32_t k = 1; k <= count; ++k) {
    const size_t seed = m.vertex_count() * k / (count + 1);
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      double d = 0;
      for (int a = 0; a < 3; ++a) d += std::pow(double(m.positions[3 * v + a]) - m.positions[3 * seed + a], 2);
      if (d < r2) gone[v] = 1;
    }
  }
  TriangleMesh out{m.positions, {}};
  for (size_t f = 0; f < m.triangle_count(); ++f)
    if (!gone[m.triangles[3 * f]] && !gone[m.triangles[3 * f + 1]] && !gone[m.triangles[3 * f + 2]])
      out.triangles.insert(out.triangles.end(), m.triangles.begin() + 3 * f, m.triangles.begin() + 3 * f + 3);
  return out;
}

}  // namespace dbss::bench
