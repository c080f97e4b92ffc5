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
    s.other_index.push_back(v);
    s.other_weight.push_back(w);
  }
  void open(uint32_t e) { s.other_odd.push_back(e); }
  void close() { s.other_offset.push_back(static_cast<uint32_t>(s.other_index.size())); }
};

constexpr double kRegular[8] = {0.5, 0.5, 1.0 / 8, 1.0 / 8, -1.0 / 16, -1.0 / 16, -1.0 / 16, -1.0 / 16};

// Third vertex of the triangle across half-edge x, or the parallelogram
// reflection of `away` across the edge when x is on the boundary (as in
// OpenMesh's ModifiedButterFlyT): the wing a + b - away with weight -1/16.
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

Stencils build_stencils(const LevelTopology& t, bool all_generic) {
  Stencils s;
  const uint32_t edges = t.edge_count();
  s.odd_count = edges;
  s.regular_odd.resize(edges);
  s.regular_index.resize(size_t{edges} * 8);
  s.other_offset.push_back(0);
  Builder b{s};
  const uint32_t* tri = t.triangles.data();
  const uint32_t* twin = t.twin.data();
  uint32_t regular = 0;
  for (uint32_t e = 0; e < edges; ++e) {
    const uint32_t h = t.edge_half[e];
    const uint32_t u = tri[h], w = tri[next_half(h)], c = tri[prev_half(h)];
    const uint32_t o = twin[h];
    if (o == kNoHalfEdge) {
      // Boundary edge: the four-point rule along the boundary polygon.  h is
      // u's outgoing boundary half-edge; u's incoming one ends its fan.
      uint32_t x = h;
      for (uint32_t n = t.vertex_valence[u]; n > 1 && twin[prev_half(x)] != kNoHalfEdge; --n) x = twin[prev_half(x)];
      b.open(e);
      b.add(tri[prev_half(x)], -1.0 / 16);
      b.add(u, 9.0 / 16);
      b.add(w, 9.0 / 16);
      b.add(tri[next_half(t.vertex_start[w])], -1.0 / 16);
      b.close();
      continue;
    }
    const uint32_t d = tri[prev_half(o)];
    const bool bu = t.vertex_boundary[u], bw = t.vertex_boundary[w];
    const bool xu = !bu && t.vertex_valence[u] != 6;
    const bool xw = !bw && t.vertex_valence[w] != 6;
    if (!xu && !xw && !bu && !bw && !all_generic) {
      // Both ends interior: all four wings exist.
      uint32_t* r = &s.regular_index[8 * size_t{regular}];
      r[0] = u, r[1] = w, r[2] = c, r[3] = d;
      r[4] = tri[prev_half(twin[next_half(h)])];
      r[5] = tri[prev_half(twin[prev_half(h)])];
      r[6] = tri[prev_half(twin[next_half(o)])];
      r[7] = tri[prev_half(twin[prev_half(o)])];
      s.regular_odd[regular++] = e;
      continue;
    }
    b.open(e);
    if (!xu && !xw) {
      for (uint32_t v : {u, w, c, d}) b.add(v, v == u || v == w ? 0.5 : 1.0 / 8);
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
  s.regular_odd.resize(regular);
  s.regular_index.resize(size_t{regular} * 8);
  return s;
}

void stencil_terms(const Stencils& s, uint32_t odd, std::vector<uint32_t>& index, std::vector<double>& weight) {
  index.clear();
  weight.clear();
  for (size_t i = 0; i < s.regular_odd.size(); ++i)
    if (s.regular_odd[i] == odd) {
      index.assign(&s.regular_index[8 * i], &s.regular_index[8 * i + 8]);
      weight.assign(kRegular, kRegular + 8);
      return;
    }
  for (size_t i = 0; i < s.other_odd.size(); ++i)
    if (s.other_odd[i] == odd) {
      index.assign(&s.other_index[s.other_offset[i]], &s.other_index[s.other_offset[i + 1]]);
      weight.assign(&s.other_weight[s.other_offset[i]], &s.other_weight[s.other_offset[i + 1]]);
      return;
    }
}

void apply_stencils(const Stencils& s, const float* p, uint32_t rb, uint32_t re, uint32_t ob, uint32_t oe, float* odd) {
  // Regular stencils: the same ordered sum as the generic loop below with
  // kRegular's weights, written out so the compiler keeps it in registers.
  const uint32_t* ri = s.regular_index.data();
  for (uint32_t i = rb; i < re; ++i) {
    const uint32_t* r = ri + 8 * size_t{i};
    float* out = odd + 3 * size_t{s.regular_odd[i]};
    for (int k = 0; k < 3; ++k) {
      double a = 0;
      a = a + 0.5 * p[3 * size_t{r[0]} + k];
      a = a + 0.5 * p[3 * size_t{r[1]} + k];
      a = a + 0.125 * p[3 * size_t{r[2]} + k];
      a = a + 0.125 * p[3 * size_t{r[3]} + k];
      a = a + -0.0625 * p[3 * size_t{r[4]} + k];
      a = a + -0.0625 * p[3 * size_t{r[5]} + k];
      a = a + -0.0625 * p[3 * size_t{r[6]} + k];
      a = a + -0.0625 * p[3 * size_t{r[7]} + k];
      out[k] = static_cast<float>(a);
    }
  }
  const uint32_t* off = s.other_offset.data();
  const uint32_t* idx = s.other_index.data();
  const double* wt = s.other_weight.data();
  for (uint32_t e = ob; e < oe; ++e) {
    double x = 0, y = 0, z = 0;
    for (uint32_t i = off[e]; i < off[e + 1]; ++i) {
      const float* q = p + 3 * size_t{idx[i]};
      const double w = wt[i];
      x = x + w * q[0];
      y = y + w * q[1];
      z = z + w * q[2];
    }
    float* out = odd + 3 * size_t{s.other_odd[e]};
    out[0] = static_cast<float>(x);
    out[1] = static_cast<float>(y);
    out[2] = static_cast<float>(z);
  }
}

}  // namespace dbss
