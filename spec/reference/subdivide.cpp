// decoding.md sections 4-7: one refinement step, level l to level l+1.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "reference.h"
#include "topology.h"

namespace dbss_ref {

using namespace detail;

namespace {

// One term (vertex, weight) of a stencil (section 5).
struct Term {
  uint32_t vertex;
  double weight;
};

struct Stencil {
  std::vector<Term> terms;
  // Terms whose weight is exactly zero are omitted.
  void add(uint32_t v, double w) {
    if (w != 0.0) terms.push_back({v, w});
  }
};

// Section 3, version 1.1: the creases of a level and the kinds of vertex
// they make. Without creases every vector is all zero.
struct Creases {
  std::vector<uint8_t> edge;   // per edge
  std::vector<uint8_t> sharp;  // per vertex: crease count >= 1 or corner
  std::vector<uint8_t> end;    // per vertex: sharp and (corner, count != 2 or boundary)
};

Creases crease_kinds(const Topology& t, const Mesh& level) {
  Creases c;
  c.edge.assign(t.edge_count(), 0);
  c.sharp.assign(t.vertex_count, 0);
  c.end.assign(t.vertex_count, 0);
  if (level.crease.empty() && level.corner.empty()) return c;
  if (level.crease.size() != t.edge_count() || level.corner.size() != t.vertex_count)
    throw std::invalid_argument("need one crease flag per edge and one corner flag per vertex");
  std::vector<uint32_t> count(t.vertex_count, 0);
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    c.edge[e] = level.crease[e] != 0;
    if (!c.edge[e]) continue;
    ++count[t.T[t.edge_half[e]]];
    ++count[t.T[next(t.edge_half[e])]];
  }
  for (uint32_t v = 0; v < t.vertex_count; ++v) {
    c.sharp[v] = count[v] >= 1 || level.corner[v];
    c.end[v] = c.sharp[v] && (level.corner[v] || count[v] != 2 || t.boundary[v]);
  }
  return c;
}

bool interior_extraordinary(const Topology& t, const Creases& c, uint32_t v) {
  return !t.boundary[v] && !c.sharp[v] && t.valence[v] != 6;  // "smooth" and not valence 6
}

// Section 5.4: the other crease neighbour of u, which is not a crease end:
// the first outgoing half-edge counter-clockwise after x0 (u -> w) whose
// edge is a crease.
uint32_t crease_neighbour(const Topology& t, const Creases& c, uint32_t x0) {
  uint32_t x = t.twin[prev(x0)];
  while (!c.edge[t.edge_of[x]]) x = t.twin[prev(x)];
  return t.T[next(x)];
}

// Section 5.4: crease edge h (u -> w, twin o).
void crease_rule(const Topology& t, const Creases& c, uint32_t h, Stencil& s) {
  const uint32_t o = t.twin[h];
  const uint32_t u = t.T[h], w = t.T[next(h)];
  if (!c.end[u] && !c.end[w]) {
    s.add(crease_neighbour(t, c, h), -1.0 / 16);
    s.add(u, 9.0 / 16);
    s.add(w, 9.0 / 16);
    s.add(crease_neighbour(t, c, o), -1.0 / 16);
  } else if (c.end[u] && !c.end[w]) {
    s.add(u, 7.0 / 16);
    s.add(w, 10.0 / 16);
    s.add(crease_neighbour(t, c, o), -1.0 / 16);
  } else if (!c.end[u] && c.end[w]) {
    s.add(crease_neighbour(t, c, h), -1.0 / 16);
    s.add(u, 10.0 / 16);
    s.add(w, 7.0 / 16);
  } else {
    s.add(u, 1.0 / 2);
    s.add(w, 1.0 / 2);
  }
}

// Section 5.1: boundary edge h (u -> w, no twin), four-point rule.
void boundary_rule(const Topology& t, uint32_t h, Stencil& s) {
  const uint32_t u = t.T[h], w = t.T[next(h)];
  // b: start of u's incoming boundary half-edge (where u's fan walk ends);
  // a: end of w's outgoing boundary half-edge.
  const uint32_t b = t.T[t.in_boundary[u]];
  const uint32_t a = t.T[next(t.out_boundary[w])];
  s.add(b, -1.0 / 16);
  s.add(u, 9.0 / 16);
  s.add(w, 9.0 / 16);
  s.add(a, -1.0 / 16);
}

// Section 5.2: the wing across half-edge x; z is the edge end not on x.
void wing(const Topology& t, const Creases& c, uint32_t x, uint32_t z, Stencil& s) {
  const uint32_t y = t.twin[x];
  if (y != kNone && !c.edge[t.edge_of[x]]) {
    s.add(t.T[prev(y)], -1.0 / 16);
  } else {
    // Reflection T[x] + T[next(x)] - z, as three terms in this order.
    s.add(t.T[x], -1.0 / 16);
    s.add(t.T[next(x)], -1.0 / 16);
    s.add(z, 1.0 / 16);
  }
}

// Section 5.2: interior edge h (u -> w, twin o), neither end interior
// extraordinary: eight-point rule with reflected wings where missing.
void regular_rule(const Topology& t, const Creases& cr, uint32_t h, Stencil& s) {
  const uint32_t o = t.twin[h];
  const uint32_t u = t.T[h], w = t.T[next(h)], c = t.T[prev(h)], d = t.T[prev(o)];
  s.add(u, 1.0 / 2);
  s.add(w, 1.0 / 2);
  s.add(c, 1.0 / 8);
  s.add(d, 1.0 / 8);
  wing(t, cr, next(h), u, s);  // w -> c
  wing(t, cr, prev(h), w, s);  // c -> u
  wing(t, cr, next(o), w, s);  // u -> d
  wing(t, cr, prev(o), u, s);  // d -> w
}

// Section 5.3: the terms of interior extraordinary end v = T[x0], where x0
// runs from v to the other end.
void extraordinary_terms(const Topology& t, uint32_t x0, double sigma, Stencil& s) {
  const uint32_t v = t.T[x0];
  const uint32_t k = t.valence[v];
  if (k < 3 || k > 64) throw std::invalid_argument("interior valence outside 3..64");
  s.add(v, 3.0 / 4 * sigma);
  uint32_t x = x0;
  for (uint32_t j = 0; j < k; ++j) {
    s.add(t.T[next(x)], butterfly_weight(k, j) * sigma);  // n_j
    x = t.twin[prev(x)];                                  // x_{j+1}
  }
}

Stencil odd_stencil(const Topology& t, const Creases& c, uint32_t h) {
  Stencil s;
  const uint32_t o = t.twin[h];
  if (o == kNone) {
    boundary_rule(t, h, s);
    return s;
  }
  if (c.edge[t.edge_of[h]]) {
    crease_rule(t, c, h, s);
    return s;
  }
  const uint32_t u = t.T[h], w = t.T[next(h)];
  const bool eu = interior_extraordinary(t, c, u), ew = interior_extraordinary(t, c, w);
  if (!eu && !ew) {
    regular_rule(t, c, h, s);
  } else {
    const double sigma = (eu && ew) ? 0.5 : 1.0;
    if (eu) extraordinary_terms(t, h, sigma, s);  // x0 = h: u -> w
    if (ew) extraordinary_terms(t, o, sigma, s);  // x0 = o: w -> u
  }
  return s;
}

// The stencil point, coordinate by coordinate, summed left to right in
// binary64 and rounded once (sections 1 and 5).
void evaluate(const Stencil& s, const std::vector<float>& P, float out[3]) {
  for (int c = 0; c < 3; ++c) {
    double a = 0.0;
    for (const Term& term : s.terms) a = a + term.weight * double(P[3 * size_t{term.vertex} + c]);
    out[c] = static_cast<float>(a);
  }
}

// Section 6: the unit normal of odd vertex m from its ring r_0..r_{n-1} of
// the undisplaced level l+1 mesh; `closed` pairs r_{n-1} with r_0.
void ring_normal(const std::vector<float>& P, uint32_t m, const uint32_t* ring, int n, bool closed,
                 double normal[3]) {
  double d[6][3];
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      d[i][c] = double(P[3 * size_t{ring[i]} + c]) - double(P[3 * size_t{m} + c]);
  double N[3] = {0.0, 0.0, 0.0};
  const int pairs = closed ? n : n - 1;
  for (int i = 0; i < pairs; ++i) {
    const double* a = d[i];
    const double* b = d[(i + 1) % n];
    N[0] = N[0] + (a[1] * b[2] - a[2] * b[1]);
    N[1] = N[1] + (a[2] * b[0] - a[0] * b[2]);
    N[2] = N[2] + (a[0] * b[1] - a[1] * b[0]);
  }
  const double len = std::sqrt((N[0] * N[0] + N[1] * N[1]) + N[2] * N[2]);
  if (len > 0) {
    const double inv = 1 / len;  // one division, computed once
    for (int c = 0; c < 3; ++c) normal[c] = N[c] * inv;
  } else {
    for (int c = 0; c < 3; ++c) normal[c] = 0.0;
  }
}

}  // namespace

Mesh subdivide(const Mesh& level, std::span<const int32_t> q, float step, std::vector<double>* normals,
               std::span<const int32_t> boundary, float boundary_step) {
  if (level.positions.size() % 3 != 0 || level.positions.size() / 3 >= kNone)
    throw std::invalid_argument("positions are not x y z triples");
  const uint32_t V = static_cast<uint32_t>(level.positions.size() / 3);
  Topology t;
  if (std::string why = build_topology(V, level.triangles, t); !why.empty())
    throw std::invalid_argument("not an oriented manifold: " + why);
  const uint32_t E = t.edge_count();
  const uint32_t F = static_cast<uint32_t>(level.triangles.size() / 3);
  if (!q.empty() && q.size() != E) throw std::invalid_argument("need one q per edge");
  uint32_t B = 0;  // boundary edges (section 3: no twin)
  for (uint32_t e = 0; e < E; ++e) B += t.twin[t.edge_half[e]] == kNone;
  if (!boundary.empty() && (q.empty() || boundary.size() != B))
    throw std::invalid_argument("need one boundary value per boundary edge, and q");

  const Creases creases = crease_kinds(t, level);

  // Section 4: even vertices keep their positions; edge e gets odd vertex V + e.
  Mesh out;
  out.positions = level.positions;
  out.positions.resize(3 * (size_t{V} + E));

  // Section 5: every odd position s, before any displacement.
  for (uint32_t e = 0; e < E; ++e)
    evaluate(odd_stencil(t, creases, t.edge_half[e]), level.positions, &out.positions[3 * (size_t{V} + e)]);

  // Sections 6 and 7: normals from the undisplaced level l+1 positions, so
  // displaced positions go to a copy until all normals are taken.
  if (normals) normals->assign(3 * size_t{E}, 0.0);
  std::vector<double> boundary_normals;  // section 7a needs section 6's n of the boundary odd vertices
  if (!q.empty() || normals) {
    std::vector<float> displaced(out.positions.begin() + 3 * size_t{V}, out.positions.end());
    const double step64 = double(step);
    for (uint32_t e = 0; e < E; ++e) {
      const uint32_t h = t.edge_half[e], o = t.twin[h];
      const uint32_t u = t.T[h], w = t.T[next(h)];
      const uint32_t m_cu = V + t.edge_of[prev(h)], m_wc = V + t.edge_of[next(h)];
      double n[3];
      if (o != kNone) {
        const uint32_t m_ud = V + t.edge_of[next(o)], m_dw = V + t.edge_of[prev(o)];
        const uint32_t ring[6] = {m_cu, u, m_ud, m_dw, w, m_wc};
        ring_normal(out.positions, V + e, ring, 6, true, n);
      } else {
        const uint32_t ring[4] = {w, m_wc, m_cu, u};
        ring_normal(out.positions, V + e, ring, 4, false, n);
      }
      if (normals) std::copy(n, n + 3, normals->begin() + 3 * size_t{e});
      if (o == kNone && !boundary.empty()) boundary_normals.insert(boundary_normals.end(), n, n + 3);
      if (q.empty()) continue;
      const double dq = double(q[e]) * step64;
      for (int c = 0; c < 3; ++c) {
        const double s = double(out.positions[3 * (size_t{V} + e) + c]);
        displaced[3 * size_t{e} + c] = static_cast<float>(s + dq * n[c]);
      }
    }
    if (!q.empty()) std::copy(displaced.begin(), displaced.end(), out.positions.begin() + 3 * size_t{V});
  }

  // Section 7a (version 1.3): the k-th boundary edge's odd vertex moves by
  // p_k * step along b = t x n / |t x n|, after section 7.
  if (!boundary.empty()) {
    const double step64 = double(boundary_step);
    uint32_t k = 0;
    for (uint32_t e = 0; e < E; ++e) {
      const uint32_t h = t.edge_half[e];
      if (t.twin[h] != kNone) continue;
      const float* u = &level.positions[3 * size_t{t.T[h]}];
      const float* w = &level.positions[3 * size_t{t.T[next(h)]}];
      const double* n = &boundary_normals[3 * size_t{k}];
      const double tv[3] = {double(w[0]) - double(u[0]), double(w[1]) - double(u[1]), double(w[2]) - double(u[2])};
      const double c[3] = {tv[1] * n[2] - tv[2] * n[1], tv[2] * n[0] - tv[0] * n[2], tv[0] * n[1] - tv[1] * n[0]};
      const double len = std::sqrt((c[0] * c[0] + c[1] * c[1]) + c[2] * c[2]);
      double b[3] = {0.0, 0.0, 0.0};
      if (len > 0) {
        const double inv = 1 / len;  // one division
        for (int i = 0; i < 3; ++i) b[i] = c[i] * inv;
      }
      if (boundary[k] == 0) {  // a zero value leaves section 7's position as it is
        ++k;
        continue;
      }
      const double dp = double(boundary[k]) * step64;
      float* m = &out.positions[3 * (size_t{V} + e)];
      for (int i = 0; i < 3; ++i) m[i] = static_cast<float>(double(m[i]) + dp * b[i]);
      ++k;
    }
  }

  // Section 4: triangle f becomes 4f+0..4f+3.
  out.triangles.resize(12 * size_t{F});
  for (uint32_t f = 0; f < F; ++f) {
    const uint32_t v0 = t.T[3 * f], v1 = t.T[3 * f + 1], v2 = t.T[3 * f + 2];
    const uint32_t m0 = V + t.edge_of[3 * f], m1 = V + t.edge_of[3 * f + 1],
                   m2 = V + t.edge_of[3 * f + 2];
    const uint32_t children[12] = {v0, m0, m2, v1, m1, m0, v2, m2, m1, m0, m1, m2};
    std::copy(children, children + 12, out.triangles.begin() + 12 * size_t{f});
  }

  // Section 4, version 1.1: the halves u-m and m-w of a crease edge are
  // creases, edges inside a triangle are not; even vertices keep their
  // corner tags, odd vertices have none.
  if (!level.crease.empty() || !level.corner.empty()) {
    Topology child;
    if (std::string why = build_topology(V + E, out.triangles, child); !why.empty())
      throw std::invalid_argument("child level: " + why);
    out.crease.assign(child.edge_count(), 0);
    for (uint32_t e = 0; e < child.edge_count(); ++e) {
      const uint32_t a = child.T[child.edge_half[e]], b = child.T[next(child.edge_half[e])];
      const uint32_t even = std::min(a, b), odd = std::max(a, b);
      if (even >= V || odd < V) continue;  // a half of a parent edge joins an even and an odd vertex
      const uint32_t parent = odd - V, h = t.edge_half[parent];
      if ((t.T[h] == even || t.T[next(h)] == even) && creases.edge[parent]) out.crease[e] = 1;
    }
    out.corner.assign(V + E, 0);
    for (uint32_t v = 0; v < V; ++v) out.corner[v] = level.corner.empty() ? 0 : level.corner[v];
  }
  return out;
}

namespace detail {
bool creases_fit(const Mesh& mesh) {
  if (mesh.crease.empty()) return true;
  Topology t;
  if (!build_topology(static_cast<uint32_t>(mesh.positions.size() / 3), mesh.triangles, t).empty()) return false;
  if (mesh.crease.size() != t.edge_count()) return false;
  for (uint32_t e = 0; e < t.edge_count(); ++e)
    if (mesh.crease[e] && t.twin[t.edge_half[e]] == kNone) return false;
  return true;
}
}  // namespace detail

uint64_t fnv1a64(const Mesh& mesh) {
  uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64 offset basis
  for (float x : mesh.positions) {
    uint32_t bits;
    static_assert(sizeof bits == sizeof x);
    std::memcpy(&bits, &x, sizeof bits);
    for (int i = 0; i < 4; ++i) {  // little-endian byte order
      h ^= (bits >> (8 * i)) & 0xFF;
      h *= 0x100000001b3ull;  // FNV 64 prime
    }
  }
  return h;
}

}  // namespace dbss_ref
