#include "dbss/decoder/butterfly.h"

namespace dbss {

namespace {
#include "butterfly_weights.inc"

struct Builder {
  Stencils& s;
  void add(uint32_t v, double w) {
    // Zero weights (valence 4) are left out so every stencil is a sum of
    // nonzero terms; adding 0 * p could only change the sign of a zero.
    if (w == 0.0) return;
    s.index.push_back(v);
    s.weight.push_back(w);
  }
  void close() { s.offset.push_back(static_cast<uint32_t>(s.index.size())); }
};

// Third vertex of the triangle across half-edge x, or the parallelogram
// reflection of `away` across the edge when x is on the boundary (as in
// OpenMesh's ModifiedButterFlyT): the wing a - b - away with weight -1/16.
void add_wing(Builder& b, const LevelTopology& t, uint32_t x, uint32_t away) {
  const uint32_t o = t.twin[x];
  if (o != kNoHalfEdge) {
    b.add(t.triangles[prev_half(o)], -1.0 / 16);
  } else {
    b.add(t.triangles[x], -1.0 / 16);
    b.add(t.triangles[next_half(x)], -1.0 / 16);
    b.add(away, 1.0 / 16);
  }
}

// Extraordinary rule of vertex v around its outgoing half-edge `out` (towards
// the edge's other end), scaled by `scale` (1, or 1/2 when both ends use it).
void add_extraordinary(Builder& b, const LevelTopology& t, uint32_t v, uint32_t out, double scale) {
  const uint32_t k = t.vertex_valence[v];
  b.add(v, 0.75 * scale);
  uint32_t x = out;
  for (uint32_t j = 0; j < k; ++j) {
    b.add(t.triangles[next_half(x)], butterfly_weight(k, j) * scale);
    x = t.twin[prev_half(x)];  // counter-clockwise; interior vertices only
  }
}

}  // namespace

double butterfly_weight(uint32_t k, uint32_t j) noexcept {
  if (k < 3 || k > kMaxValence || j >= k) return 0.0;
  return kButterflyWeights[kButterflyWeightOffset[k] + j];
}

Stencils build_stencils(const LevelTopology& t) {
  Stencils s;
  const uint32_t edges = t.edge_count();
  s.offset.reserve(edges + 1);
  s.index.reserve(size_t{edges} * 8);
  s.weight.reserve(size_t{edges} * 8);
  s.offset.push_back(0);
  Builder b{s};
  for (uint32_t e = 0; e < edges; ++e) {
    const uint32_t h = t.edge_half[e];
    const uint32_t u = t.triangles[h], w = t.triangles[next_half(h)], c = t.triangles[prev_half(h)];
    const uint32_t o = t.twin[h];
    if (o == kNoHalfEdge) {
      // Boundary edge: the four-point rule along the boundary polygon.  h is
      // u's outgoing boundary half-edge; u's incoming one ends its fan.
      uint32_t x = h;
      for (uint32_t n = t.vertex_valence[u]; n > 1 && t.twin[prev_half(x)] != kNoHalfEdge; --n) x = t.twin[prev_half(x)];
      const uint32_t before = t.triangles[prev_half(x)];
      const uint32_t after = t.triangles[next_half(t.vertex_start[w])];
      b.add(before, -1.0 / 16);
      b.add(u, 9.0 / 16);
      b.add(w, 9.0 / 16);
      b.add(after, -1.0 / 16);
      b.close();
      continue;
    }
    const uint32_t d = t.triangles[prev_half(o)];
    const bool xu = !t.vertex_boundary[u] && t.vertex_valence[u] != 6;
    const bool xw = !t.vertex_boundary[w] && t.vertex_valence[w] != 6;
    if (!xu && !xw) {
      b.add(u, 0.5);
      b.add(w, 0.5);
      b.add(c, 1.0 / 8);
      b.add(d, 1.0 / 8);
      add_wing(b, t, next_half(h), u);  // across w-c
      add_wing(b, t, prev_half(h), w);  // across c-u
      add_wing(b, t, next_half(o), w);  // across u-d
      add_wing(b, t, prev_half(o), u);  // across d-w
    } else {
      const double scale = xu && xw ? 0.5 : 1.0;
      if (xu) add_extraordinary(b, t, u, h, scale);
      if (xw) add_extraordinary(b, t, w, o, scale);
    }
    b.close();
  }
  return s;
}

void apply_stencils(const Stencils& s, const float* p, uint32_t begin, uint32_t end, float* odd) {
  const uint32_t* off = s.offset.data();
  const uint32_t* idx = s.index.data();
  const double* wt = s.weight.data();
  for (uint32_t e = begin; e < end; ++e, odd += 3) {
    double x = 0, y = 0, z = 0;
    for (uint32_t i = off[e]; i < off[e + 1]; ++i) {
      const float* q = p + 3 * size_t{idx[i]};
      const double w = wt[i];
      x = x + w * q[0];
      y = y + w * q[1];
      z = z + w * q[2];
    }
    odd[0] = static_cast<float>(x);
    odd[1] = static_cast<float>(y);
    odd[2] = static_cast<float>(z);
  }
}

}  // namespace dbss
