// Internal: the Modified Butterfly terms of one edge (spec/decoding.md
// section 5), written once and used both to tabulate stencils
// (build_stencils) and to evaluate them on the fly (the progressive decoder).
#pragma once

#include "butterfly_weight.h"
#include "topology_ref.h"

namespace dbss::detail {

// Both ends interior with valence 6: the fixed 8-point rule.
inline bool regular_end(const TopologyRef& t, uint32_t v) noexcept { return !t.boundary[v] && t.valence[v] == 6; }

// The 8 vertices of a regular stencil for the edge of half-edge h (twin o):
// u, w, c, d, then the wings across w-c, c-u, u-d, d-w.
// Always inlined: out of line, r[] would go through memory (WebAssembly's
// SIMD build left it so).
__attribute__((always_inline)) inline void regular_vertices(const TopologyRef& t, uint32_t h, uint32_t o, uint32_t r[8]) noexcept {
  const uint32_t* tri = t.tri;
  r[0] = tri[h], r[1] = tri[next_half(h)], r[2] = tri[prev_half(h)], r[3] = across_of(t, h);
  r[4] = across_of(t, next_half(h));
  r[5] = across_of(t, prev_half(h));
  r[6] = across_of(t, next_half(o));
  r[7] = across_of(t, prev_half(o));
}

inline constexpr double kRegularWeights[8] = {0.5, 0.5, 1.0 / 8, 1.0 / 8, -1.0 / 16, -1.0 / 16, -1.0 / 16, -1.0 / 16};

// Calls sink.add(vertex, weight) for each term of the edge opened by
// half-edge h, in the spec's order, zero weights left out (adding 0 * p
// could only change the sign of a zero).  Handles every kind of edge; the
// regular one is faster through regular_vertices().
template <class Sink>
void edge_terms(const TopologyRef& t, uint32_t h, Sink& b) {
  const uint32_t* tri = t.tri;
  const uint32_t* twin = t.twin;
  const auto add = [&](uint32_t v, double w) {
    if (w != 0.0) b.add(v, w);
  };
  const uint32_t u = tri[h], w = tri[next_half(h)];
  const uint32_t o = twin[h];
  if (o == kNoHalfEdge) {
    // Boundary edge: the four-point rule along the boundary polygon.  h is
    // u's outgoing boundary half-edge; u's incoming one ends its fan.
    uint32_t x = h;
    for (uint32_t n = t.valence[u]; n > 1 && twin[prev_half(x)] != kNoHalfEdge; --n) x = twin[prev_half(x)];
    add(tri[prev_half(x)], -1.0 / 16);
    add(u, 9.0 / 16);
    add(w, 9.0 / 16);
    add(tri[next_half(t.vertex_start[w])], -1.0 / 16);
    return;
  }
  // Creases (spec section 5.4) are a boundary inside the mesh.  Only this
  // generic path sees them: an edge whose ends are both smooth interior
  // vertices (the fast path) has no crease among its wings.
  const uint8_t* crease = t.crease;
  const auto on_crease = [&](uint32_t x) { return crease && crease[t.edge_of[x]]; };
  if (on_crease(h)) {
    // The four-point rule along the crease polyline.  b (before u) and a
    // (after w) are the other crease neighbours of u and w; at a polyline
    // end the missing point is the reflection 2u - w (or 2w - u), folded
    // into the weights so each vertex appears once.
    const auto other = [&](uint32_t x, uint32_t v) {  // x: an outgoing half-edge of v, on this crease
      for (uint32_t n = t.valence[v]; n > 1; --n) {
        x = twin[prev_half(x)];  // counter-clockwise; v is interior (not an end)
        if (on_crease(x)) break;
      }
      return tri[next_half(x)];
    };
    const bool end_u = t.boundary[u] & kVertexCreaseEnd, end_w = t.boundary[w] & kVertexCreaseEnd;
    if (end_u && end_w) {  // both reflected: the midpoint
      add(u, 0.5), add(w, 0.5);
      return;
    }
    if (!end_u) add(other(h, u), -1.0 / 16);
    add(u, end_u ? 7.0 / 16 : end_w ? 10.0 / 16 : 9.0 / 16);
    add(w, end_w ? 7.0 / 16 : end_u ? 10.0 / 16 : 9.0 / 16);
    if (!end_w) add(other(o, w), -1.0 / 16);
    return;
  }
  const bool xu = !t.boundary[u] && t.valence[u] != 6;
  const bool xw = !t.boundary[w] && t.valence[w] != 6;
  if (!xu && !xw) {
    // Third vertex of the triangle across half-edge x, or the parallelogram
    // reflection of `away` across the edge when x is on the boundary or a
    // crease (as in OpenMesh's ModifiedButterFlyT): the wing a + b - away,
    // weight -1/16.
    const auto wing = [&](uint32_t x, uint32_t away) {
      const uint32_t y = twin[x];
      if (y != kNoHalfEdge && !on_crease(x)) {
        add(tri[prev_half(y)], -1.0 / 16);
      } else {
        add(tri[x], -1.0 / 16);
        add(tri[next_half(x)], -1.0 / 16);
        add(away, 1.0 / 16);
      }
    };
    const uint32_t c = tri[prev_half(h)], d = tri[prev_half(o)];
    add(u, 0.5), add(w, 0.5), add(c, 1.0 / 8), add(d, 1.0 / 8);
    wing(next_half(h), u);  // across w-c
    wing(prev_half(h), w);  // across c-u
    wing(next_half(o), w);  // across u-d
    wing(prev_half(o), u);  // across d-w
    return;
  }
  // Extraordinary rule of vertex v around its outgoing half-edge `out`
  // (towards the other end), scaled by 1/2 when both ends use it.
  const double scale = xu && xw ? 0.5 : 1.0;
  const auto extraordinary = [&](uint32_t v, uint32_t out) {
    const uint32_t k = t.valence[v];
    add(v, 0.75 * scale);
    uint32_t x = out;
    for (uint32_t j = 0; j < k; ++j) {
      add(tri[next_half(x)], butterfly_weight(k, j) * scale);
      x = twin[prev_half(x)];  // counter-clockwise; interior vertices only
    }
  };
  if (xu) extraordinary(u, h);
  if (xw) extraordinary(w, o);
}

}  // namespace dbss::detail
