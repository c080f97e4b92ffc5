// decoding.md section 7a: boundary odd vertices moved across the boundary.
#include "boundary_shift.h"

#include <cmath>

namespace dbss::detail {

namespace {

// Section 6's unit normal of the boundary odd vertex of half-edge h: ring
// w, m_wc, m_cu, u and three pairs, each term as the spec writes it (the
// kernels compute the same bits in their own layout).
void boundary_normal(const TopologyRef& t, const float* p, const float* per_half, uint32_t h, double n[3]) {
  const float* m = per_half + 3 * size_t{h};
  const float* ring[4] = {p + 3 * size_t{t.tri[next_half(h)]}, per_half + 3 * size_t{next_half(h)},
                          per_half + 3 * size_t{prev_half(h)}, p + 3 * size_t{t.tri[h]}};
  double d[4][3];
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) d[i][c] = double{ring[i][c]} - double{m[c]};
  double N[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const double* a = d[i];
    const double* b = d[i + 1];
    N[0] = N[0] + (a[1] * b[2] - a[2] * b[1]);
    N[1] = N[1] + (a[2] * b[0] - a[0] * b[2]);
    N[2] = N[2] + (a[0] * b[1] - a[1] * b[0]);
  }
  const double len = std::sqrt((N[0] * N[0] + N[1] * N[1]) + N[2] * N[2]);
  if (len > 0) {
    const double inv = 1.0 / len;
    for (int c = 0; c < 3; ++c) n[c] = N[c] * inv;
  } else {
    n[0] = n[1] = n[2] = 0;
  }
}

}  // namespace

void shift_boundary(const TopologyRef& t, const float* p, const float* per_half, const int32_t* bq,
                    const BoundaryChooser* choose, int32_t* chosen, float step, float* out_odd) {
  const double delta = step;
  uint32_t k = 0;
  for (uint32_t e = 0; e < t.edge_count; ++e) {
    const uint32_t h = t.edge_half[e];
    if (t.twin[h] != kNoHalfEdge) continue;
    const float* u = p + 3 * size_t{t.tri[h]};
    const float* w = p + 3 * size_t{t.tri[next_half(h)]};
    double n[3];
    boundary_normal(t, p, per_half, h, n);
    const double tv[3] = {double{w[0]} - double{u[0]}, double{w[1]} - double{u[1]}, double{w[2]} - double{u[2]}};
    const double c[3] = {tv[1] * n[2] - tv[2] * n[1], tv[2] * n[0] - tv[0] * n[2], tv[0] * n[1] - tv[1] * n[0]};
    const double len = std::sqrt((c[0] * c[0] + c[1] * c[1]) + c[2] * c[2]);
    double b[3] = {0, 0, 0};
    if (len > 0) {
      const double inv = 1.0 / len;
      for (int i = 0; i < 3; ++i) b[i] = c[i] * inv;
    }
    float* m = out_odd + 3 * size_t{e};
    int32_t value;
    if (choose) {
      value = (*choose)(k, e, m, b, n, u, w);
      chosen[k] = value;
    } else {
      value = bq[k];
    }
    ++k;
    // Section 7a moves only vertices with a value (-0 + +0 would be +0).
    if (value == 0) continue;
    const double dp = static_cast<double>(value) * delta;
    for (int i = 0; i < 3; ++i) m[i] = static_cast<float>(double{m[i]} + dp * b[i]);
  }
}

}  // namespace dbss::detail
