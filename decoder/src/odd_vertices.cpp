#include "odd_vertices.h"

#include <cmath>

#include "butterfly_terms.h"

namespace dbss::detail {

namespace {

// Sums terms as apply_stencils does: a = a + w * p, from a = 0, in order.
struct Sum {
  const float* p;
  double x = 0, y = 0, z = 0;
  void add(uint32_t v, double w) {
    const float* q = p + 3 * size_t{v};
    x = x + w * q[0];
    y = y + w * q[1];
    z = z + w * q[2];
  }
};

// The regular 8-point rule, written out so it stays in registers; the
// weights and order are kRegularWeights'.
inline void regular_point(const float* p, const uint32_t r[8], float* out) {
  const float* a = p + 3 * size_t{r[0]};
  const float* b = p + 3 * size_t{r[1]};
  const float* c = p + 3 * size_t{r[2]};
  const float* d = p + 3 * size_t{r[3]};
  const float* e = p + 3 * size_t{r[4]};
  const float* f = p + 3 * size_t{r[5]};
  const float* g = p + 3 * size_t{r[6]};
  const float* h = p + 3 * size_t{r[7]};
  for (int k = 0; k < 3; ++k) {
    double s = 0;
    s = s + 0.5 * a[k];
    s = s + 0.5 * b[k];
    s = s + 0.125 * c[k];
    s = s + 0.125 * d[k];
    s = s + -0.0625 * e[k];
    s = s + -0.0625 * f[k];
    s = s + -0.0625 * g[k];
    s = s + -0.0625 * h[k];
    out[k] = static_cast<float>(s);
  }
}

// A vector from the odd vertex m to a ring vertex, in binary64.
struct D3 {
  double x, y, z;
};
inline D3 from(const float* m, const float* r) {
  return {double{r[0]} - m[0], double{r[1]} - m[1], double{r[2]} - m[2]};
}
inline void add_cross(D3& n, const D3& a, const D3& b) {
  n.x = n.x + (a.y * b.z - a.z * b.y);
  n.y = n.y + (a.z * b.x - a.x * b.z);
  n.z = n.z + (a.x * b.y - a.y * b.x);
}

}  // namespace

void stencil_points(const TopologyRef& t, const float* p, uint32_t fb, uint32_t fe, float* odd) {
  uint32_t e = first_edge_of_face(t, fb);
  for (uint32_t h = 3 * fb; h < 3 * fe; ++h) {
    const uint32_t o = t.twin[h];
    if (o < h) continue;  // the edge was opened by its twin
    float* out = odd + 3 * size_t{e++};
    if (o != kNoHalfEdge && regular_end(t, t.tri[h]) && regular_end(t, t.tri[next_half(h)])) {
      uint32_t r[8];
      regular_vertices(t, h, o, r);
      regular_point(p, r, out);
    } else {
      Sum s{p};
      edge_terms(t, h, s);
      out[0] = static_cast<float>(s.x), out[1] = static_cast<float>(s.y), out[2] = static_cast<float>(s.z);
    }
  }
}

void displaced_points(const TopologyRef& t, const float* p, const float* odd, const int32_t* q, float step,
                      uint32_t fb, uint32_t fe, float* out) {
  const double delta = step;
  const auto pos = [&](uint32_t v) { return p + 3 * size_t{v}; };
  const auto mid = [&](uint32_t x) { return odd + 3 * size_t{t.edge_of[x]}; };  // odd vertex of half-edge x
  uint32_t e = first_edge_of_face(t, fb);
  for (uint32_t h = 3 * fb; h < 3 * fe; ++h) {
    const uint32_t o = t.twin[h];
    if (o < h) continue;
    const float* m = odd + 3 * size_t{e};
    const float* u = pos(t.tri[h]);
    const float* w = pos(t.tri[next_half(h)]);
    // Ring counter-clockwise around m and its consecutive pairs (the table
    // of spec section 6).
    D3 n{0, 0, 0};
    if (o != kNoHalfEdge) {
      const D3 r0 = from(m, mid(prev_half(h))), r1 = from(m, u), r2 = from(m, mid(next_half(o)));
      const D3 r3 = from(m, mid(prev_half(o))), r4 = from(m, w), r5 = from(m, mid(next_half(h)));
      add_cross(n, r0, r1);
      add_cross(n, r1, r2);
      add_cross(n, r2, r3);
      add_cross(n, r3, r4);
      add_cross(n, r4, r5);
      add_cross(n, r5, r0);
    } else {
      const D3 r0 = from(m, w), r1 = from(m, mid(next_half(h))), r2 = from(m, mid(prev_half(h))), r3 = from(m, u);
      add_cross(n, r0, r1);
      add_cross(n, r1, r2);
      add_cross(n, r2, r3);
    }
    const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (len > 0) {
      const double inv = 1.0 / len;
      n = {n.x * inv, n.y * inv, n.z * inv};
    } else {
      n = {0, 0, 0};
    }
    const double d = static_cast<double>(q[e]) * delta;
    float* v = out + 3 * size_t{e};
    v[0] = static_cast<float>(m[0] + d * n.x);
    v[1] = static_cast<float>(m[1] + d * n.y);
    v[2] = static_cast<float>(m[2] + d * n.z);
    ++e;
  }
}

}  // namespace dbss::detail
