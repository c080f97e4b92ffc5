#include "odd_vertices.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>

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

// The kernels are written once and instantiated twice (see the end of the
// file): for the baseline instruction set and, on x86, for AVX2.
#define DBSS_KERNEL [[gnu::always_inline]] inline

DBSS_KERNEL void stencil_points_impl(const TopologyRef& t, const float* p, uint32_t fb, uint32_t fe, float* odd,
                                     float* per_half) {
  // Edges in order through edge_half, so there is no per-half-edge test
  // (and branch) whether it opens an edge.
  constexpr uint32_t kAhead = 32;
  const uint32_t end = first_edge_of_face(t, fe);
  for (uint32_t e = first_edge_of_face(t, fb); e < end; ++e) {
    // The twin triangle is the far-away access (its across entries, and
    // the point written there): request it some edges ahead.  A hint only:
    // nothing is read through it.
    if (e + kAhead < end) {
      const uint32_t ahead = t.twin[t.edge_half[e + kAhead]];
      if (ahead != kNoHalfEdge && t.across) __builtin_prefetch(t.across + 3 * (ahead / 3));
      if (ahead != kNoHalfEdge && per_half) __builtin_prefetch(per_half + 3 * size_t{ahead}, 1);
    }
    const uint32_t h = t.edge_half[e], o = t.twin[h];
    float point[3];
    if (o != kNoHalfEdge && regular_end(t, t.tri[h]) && regular_end(t, t.tri[next_half(h)])) {
      uint32_t r[8];
      regular_vertices(t, h, o, r);
      regular_point(p, r, point);
    } else {
      Sum s{p};
      edge_terms(t, h, s);
      point[0] = static_cast<float>(s.x), point[1] = static_cast<float>(s.y), point[2] = static_cast<float>(s.z);
    }
    if (odd) {
      float* out = odd + 3 * size_t{e};
      out[0] = point[0], out[1] = point[1], out[2] = point[2];
    } else {
      float* out = per_half + 3 * size_t{h};
      out[0] = point[0], out[1] = point[1], out[2] = point[2];
      if (o != kNoHalfEdge) {
        out = per_half + 3 * size_t{o};
        out[0] = point[0], out[1] = point[1], out[2] = point[2];
      }
    }
  }
}

// q_of(e, point, normal) gives odd vertex e's integer: the decoder reads it
// from the file, the encoder chooses it from the undisplaced point and the
// normal this very loop computed (so both place the vertex identically).
template <class QOf>
DBSS_KERNEL void displaced_points_impl(const TopologyRef& t, const float* p, const float* per_half, QOf&& q_of,
                                       float step, uint32_t fb, uint32_t fe, float* out) {
  const double delta = step;
  const auto pos = [&](uint32_t v) { return p + 3 * size_t{v}; };
  const auto mid = [&](uint32_t x) { return per_half + 3 * size_t{x}; };  // odd vertex of half-edge x
  // Edges go in batches of consecutive numbers, stored lane by lane
  // (structure of arrays) so that the arithmetic loops below run on several
  // edges per instruction; each lane still performs the spec's own sequence
  // of binary64 operations.  First the gathers (bound by memory), then the
  // ring sums, then lengths, square roots and divisions.
  constexpr uint32_t kBatch = 32;
  // Ring vertices r[k][coordinate][lane] and the odd vertex itself; lanes
  // past a short batch keep earlier, finite values.
  double r[6][3][kBatch] = {}, mx[kBatch] = {}, my[kBatch] = {}, mz[kBatch] = {};
  double nx[kBatch] = {}, ny[kBatch] = {}, nz[kBatch] = {};
  uint32_t border[kBatch];  // boundary edges of the batch: 4-vertex rings, summed apart
  D3 border_sum[kBatch];
  const uint32_t end = first_edge_of_face(t, fe);
  for (uint32_t e0 = first_edge_of_face(t, fb); e0 < end; e0 += kBatch) {
    const uint32_t n = std::min(kBatch, end - e0);
    // The twin triangle's points are the one far-away read (the stencil
    // pass wrote them long ago): request the next batch's now.
    for (uint32_t e = e0 + kBatch; e < std::min(end, e0 + 2 * kBatch); ++e) {
      const uint32_t o = t.twin[t.edge_half[e]];
      if (o != kNoHalfEdge) __builtin_prefetch(mid(3 * (o / 3)));
    }
    uint32_t borders = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t h = t.edge_half[e0 + i], o = t.twin[h];
      const float* m = mid(h);
      const float* u = pos(t.tri[h]);
      const float* w = pos(t.tri[next_half(h)]);
      mx[i] = m[0], my[i] = m[1], mz[i] = m[2];
      if (o != kNoHalfEdge) {
        // Ring counter-clockwise around m: m_cu, u, m_ud, m_dw, w, m_wc
        // (spec section 6).
        const float* ring[6] = {mid(prev_half(h)), u, mid(next_half(o)), mid(prev_half(o)), w, mid(next_half(h))};
        for (int k = 0; k < 6; ++k) r[k][0][i] = ring[k][0], r[k][1][i] = ring[k][1], r[k][2][i] = ring[k][2];
      } else {
        // Boundary: w, m_wc, m_cu, u and three pairs; rare, so plain code.
        const D3 r0 = from(m, w), r1 = from(m, mid(next_half(h))), r2 = from(m, mid(prev_half(h))), r3 = from(m, u);
        D3 sum{0, 0, 0};
        add_cross(sum, r0, r1);
        add_cross(sum, r1, r2);
        add_cross(sum, r2, r3);
        border[borders] = i, border_sum[borders++] = sum;
      }
    }
    for (uint32_t i = 0; i < kBatch; ++i) {
      double dx[6], dy[6], dz[6];
      for (int k = 0; k < 6; ++k) dx[k] = r[k][0][i] - mx[i], dy[k] = r[k][1][i] - my[i], dz[k] = r[k][2][i] - mz[i];
      double sx = 0, sy = 0, sz = 0;
      for (int k = 0; k < 6; ++k) {  // pairs (r_k, r_{k+1 mod 6})
        const int j = k == 5 ? 0 : k + 1;
        sx = sx + (dy[k] * dz[j] - dz[k] * dy[j]);
        sy = sy + (dz[k] * dx[j] - dx[k] * dz[j]);
        sz = sz + (dx[k] * dy[j] - dy[k] * dx[j]);
      }
      nx[i] = sx, ny[i] = sy, nz[i] = sz;
    }
    for (uint32_t b = 0; b < borders; ++b) {
      const uint32_t i = border[b];
      nx[i] = border_sum[b].x, ny[i] = border_sum[b].y, nz[i] = border_sum[b].z;
    }
    // Unit normals; zero when the length is zero.  Two plain loops so the
    // compiler vectorises them: the products with 1/len are computed for
    // every lane (a discarded 1/0 raises no trap) and selected afterwards.
    double len[kBatch];
    for (uint32_t i = 0; i < kBatch; ++i) {
      len[i] = std::sqrt(nx[i] * nx[i] + ny[i] * ny[i] + nz[i] * nz[i]);
      const double inv = 1.0 / len[i];
      nx[i] = nx[i] * inv, ny[i] = ny[i] * inv, nz[i] = nz[i] * inv;
    }
    // len > 0 (not zero, not NaN) on the bit patterns, as a mask: integer
    // operations vectorise where a floating-point select would not.
    for (uint32_t i = 0; i < kBatch; ++i) {
      const uint64_t keep = std::bit_cast<uint64_t>(len[i]) - 1 < 0x7FF0000000000000u ? ~uint64_t{0} : 0;
      nx[i] = std::bit_cast<double>(std::bit_cast<uint64_t>(nx[i]) & keep);
      ny[i] = std::bit_cast<double>(std::bit_cast<uint64_t>(ny[i]) & keep);
      nz[i] = std::bit_cast<double>(std::bit_cast<uint64_t>(nz[i]) & keep);
    }
    for (uint32_t i = 0; i < n; ++i) {
      const double d = static_cast<double>(q_of(e0 + i, mx[i], my[i], mz[i], nx[i], ny[i], nz[i])) * delta;
      float* v = out + 3 * size_t{e0 + i};
      v[0] = static_cast<float>(mx[i] + d * nx[i]);
      v[1] = static_cast<float>(my[i] + d * ny[i]);
      v[2] = static_cast<float>(mz[i] + d * nz[i]);
    }
  }
}

// The decoder's q_of: the file's integers.
struct FromFile {
  const int32_t* q;
  int32_t operator()(uint32_t e, double, double, double, double, double, double) const { return q[e]; }
};

// Each lane of every vector instruction is the IEEE operation the scalar
// code names (no FMA: the build has -ffp-contract=off, and AVX2 alone does
// not enable FMA instructions), so both instantiations give the same bits;
// tests run both (DBSS_BASELINE_KERNELS=1 forces the baseline).
#if defined(__x86_64__) && defined(__GNUC__)
#define DBSS_HAVE_AVX2_KERNELS 1
[[gnu::target("avx2")]] void stencil_points_avx2(const TopologyRef& t, const float* p, uint32_t fb, uint32_t fe,
                                                 float* odd, float* per_half) {
  stencil_points_impl(t, p, fb, fe, odd, per_half);
}
[[gnu::target("avx2")]] void displaced_points_avx2(const TopologyRef& t, const float* p, const float* per_half,
                                                   const int32_t* q, float step, uint32_t fb, uint32_t fe,
                                                   float* out) {
  displaced_points_impl(t, p, per_half, FromFile{q}, step, fb, fe, out);
}
#endif

namespace {
bool use_avx2() {
#ifdef DBSS_HAVE_AVX2_KERNELS
  static const bool cpu = __builtin_cpu_supports("avx2");
  return cpu && !std::getenv("DBSS_BASELINE_KERNELS");
#else
  return false;
#endif
}
}  // namespace

void stencil_points(const TopologyRef& t, const float* p, uint32_t fb, uint32_t fe, float* odd, float* per_half) {
#ifdef DBSS_HAVE_AVX2_KERNELS
  if (use_avx2()) return stencil_points_avx2(t, p, fb, fe, odd, per_half);
#endif
  stencil_points_impl(t, p, fb, fe, odd, per_half);
}

void displaced_points(const TopologyRef& t, const float* p, const float* per_half, const int32_t* q, float step,
                      uint32_t fb, uint32_t fe, float* out) {
#ifdef DBSS_HAVE_AVX2_KERNELS
  if (use_avx2()) return displaced_points_avx2(t, p, per_half, q, step, fb, fe, out);
#endif
  displaced_points_impl(t, p, per_half, FromFile{q}, step, fb, fe, out);
}

void displaced_points_chosen(const TopologyRef& t, const float* p, const float* per_half, const OddChooser& choose,
                             int32_t* q, float step, uint32_t fb, uint32_t fe, float* out) {
  const auto chosen = [&](uint32_t e, double mx, double my, double mz, double nx, double ny, double nz) {
    const uint32_t h = t.edge_half[e];
    const double point[3] = {mx, my, mz}, normal[3] = {nx, ny, nz};
    q[e] = choose(e, point, normal, p + 3 * size_t{t.tri[h]}, p + 3 * size_t{t.tri[next_half(h)]});
    return q[e];
  };
  displaced_points_impl(t, p, per_half, chosen, step, fb, fe, out);
}

}  // namespace dbss::detail
