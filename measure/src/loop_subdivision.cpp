#include "dbss/measure/loop_subdivision.h"

#include <cmath>
#include <numbers>

namespace dbss {

double loop_beta(uint32_t k) noexcept {
  const double c = 0.375 + 0.25 * std::cos(2 * std::numbers::pi / k);
  return (0.625 - c * c) / k;
}

void loop_subdivide(const LevelTopology& t, std::span<const float> p, std::vector<float>& out) {
  const uint32_t nv = t.vertex_count, ne = t.edge_count();
  out.assign(3 * (size_t{nv} + ne), 0.0f);
  auto at = [&](uint32_t v, int a) { return double{p[3 * size_t{v} + a]}; };
  for (uint32_t v = 0; v < nv; ++v) {
    double sum[3] = {0, 0, 0};
    uint32_t h = t.vertex_start[v];
    const uint32_t k = t.vertex_valence[v];
    double s[3];
    if (t.vertex_boundary[v]) {
      // The two boundary neighbours: the end of the outgoing boundary
      // half-edge and the start of the last incoming one around the fan.
      const uint32_t b0 = t.triangles[next_half(h)];
      while (t.twin[prev_half(h)] != kNoHalfEdge) h = t.twin[prev_half(h)];
      const uint32_t b1 = t.triangles[prev_half(h)];
      for (int a = 0; a < 3; ++a) s[a] = 0.75 * at(v, a) + 0.125 * (at(b0, a) + at(b1, a));
    } else {
      for (uint32_t i = 0; i < k; ++i, h = t.twin[prev_half(h)])
        for (int a = 0; a < 3; ++a) sum[a] += at(t.triangles[next_half(h)], a);
      const double beta = loop_beta(k);
      for (int a = 0; a < 3; ++a) s[a] = (1 - k * beta) * at(v, a) + beta * sum[a];
    }
    for (int a = 0; a < 3; ++a) out[3 * size_t{v} + a] = static_cast<float>(s[a]);
  }
  for (uint32_t e = 0; e < ne; ++e) {
    const uint32_t h = t.edge_half[e];
    const uint32_t u = t.triangles[h], w = t.triangles[next_half(h)];
    float* o = &out[3 * (size_t{nv} + e)];
    const uint32_t tw = t.twin[h];
    if (tw == kNoHalfEdge) {
      for (int a = 0; a < 3; ++a) o[a] = static_cast<float>(0.5 * (at(u, a) + at(w, a)));
      continue;
    }
    const uint32_t c = t.triangles[prev_half(h)], d = t.triangles[prev_half(tw)];
    for (int a = 0; a < 3; ++a) o[a] = static_cast<float>(0.375 * (at(u, a) + at(w, a)) + 0.125 * (at(c, a) + at(d, a)));
  }
}

}  // namespace dbss
