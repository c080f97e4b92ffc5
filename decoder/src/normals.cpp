#include "normals.h"

#include <cmath>

namespace dbss {

std::vector<uint32_t> build_odd_rings(const LevelTopology& t) {
  const uint32_t edges = t.edge_count();
  const uint32_t base = t.vertex_count;
  std::vector<uint32_t> rings(size_t{edges} * 6);
  uint32_t* r = rings.data();
  for (uint32_t e = 0; e < edges; ++e, r += 6) {
    const uint32_t h = t.edge_half[e], o = t.twin[h];
    const uint32_t u = t.triangles[h], w = t.triangles[next_half(h)];
    const uint32_t m_cu = base + t.edge_of[prev_half(h)], m_wc = base + t.edge_of[next_half(h)];
    if (o == kNoHalfEdge) {
      r[0] = w, r[1] = m_wc, r[2] = m_cu, r[3] = u, r[4] = kNoHalfEdge, r[5] = kNoHalfEdge;
    } else {
      r[0] = m_cu, r[1] = u, r[2] = base + t.edge_of[next_half(o)], r[3] = base + t.edge_of[prev_half(o)], r[4] = w,
      r[5] = m_wc;
    }
  }
  return rings;
}

void odd_normals(const uint32_t* rings, const float* p, uint32_t first_odd, uint32_t begin, uint32_t end,
                 double* normals) {
  for (uint32_t e = begin; e < end; ++e, normals += 3) {
    const uint32_t* r = rings + 6 * size_t{e};
    const float* m = p + 3 * (size_t{first_odd} + e);
    // Vectors from m to each ring vertex, then the cross products summed in
    // the spec's order: plain binary64 operations, so every build agrees.
    double d[6][3];
    const uint32_t count = r[4] == kNoHalfEdge ? 4 : 6;
    for (uint32_t i = 0; i < count; ++i) {
      const float* a = p + 3 * size_t{r[i]};
      d[i][0] = double{a[0]} - m[0], d[i][1] = double{a[1]} - m[1], d[i][2] = double{a[2]} - m[2];
    }
    double nx = 0, ny = 0, nz = 0;
    const uint32_t pairs = count == 6 ? 6 : 3;
    for (uint32_t i = 0; i < pairs; ++i) {
      const double* a = d[i];
      const double* b = d[i + 1 == count ? 0 : i + 1];
      nx = nx + (a[1] * b[2] - a[2] * b[1]);
      ny = ny + (a[2] * b[0] - a[0] * b[2]);
      nz = nz + (a[0] * b[1] - a[1] * b[0]);
    }
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (len > 0) {
      const double inv = 1.0 / len;
      normals[0] = nx * inv, normals[1] = ny * inv, normals[2] = nz * inv;
    } else {
      normals[0] = normals[1] = normals[2] = 0;
    }
  }
}

}  // namespace dbss
