// decoding.md section 3 (half-edges, edge order, valence, fans) and the
// manifold conditions of section 2 step 5.
#include "topology.h"

#include <algorithm>
#include <utility>

namespace dbss_ref::detail {

namespace {

uint64_t key(uint32_t from, uint32_t to) { return (uint64_t{from} << 32) | to; }

}  // namespace

std::string build_topology(uint32_t vertex_count, const std::vector<uint32_t>& triangles,
                           Topology& t) {
  if (triangles.size() % 3 != 0) return "corner count not a multiple of 3";
  if (triangles.size() >= kNone) return "too many half-edges";
  const uint32_t H = static_cast<uint32_t>(triangles.size());
  t = Topology{};
  t.vertex_count = vertex_count;
  t.T = triangles;

  // Section 2 step 5: no triangle repeats a vertex.
  for (uint32_t f = 0; f < H; f += 3) {
    const uint32_t a = t.T[f], b = t.T[f + 1], c = t.T[f + 2];
    if (a >= vertex_count || b >= vertex_count || c >= vertex_count) return "corner out of range";
    if (a == b || b == c || c == a) return "triangle repeats a vertex";
  }

  // Directed half-edges sorted by (from, to). A directed edge that occurs
  // twice means an edge used twice in the same direction (or by three or
  // more triangles): not an oriented manifold.
  std::vector<std::pair<uint64_t, uint32_t>> directed(H);
  for (uint32_t h = 0; h < H; ++h) directed[h] = {key(t.T[h], t.T[next(h)]), h};
  std::sort(directed.begin(), directed.end());
  for (uint32_t i = 1; i < H; ++i)
    if (directed[i].first == directed[i - 1].first) return "edge used twice in one direction";

  // twin(h): the half-edge running the other way on the same edge.
  t.twin.assign(H, kNone);
  for (uint32_t h = 0; h < H; ++h) {
    const uint64_t k = key(t.T[next(h)], t.T[h]);
    auto it = std::lower_bound(directed.begin(), directed.end(), std::make_pair(k, uint32_t{0}));
    if (it != directed.end() && it->first == k) t.twin[h] = it->second;
  }

  // Canonical edge order: h opens the next edge if it has no twin or its
  // twin comes later, so edges are numbered by their smaller half-edge.
  t.edge_of.assign(H, kNone);
  for (uint32_t h = 0; h < H; ++h) {
    if (t.twin[h] == kNone || t.twin[h] > h) {
      const uint32_t e = static_cast<uint32_t>(t.edge_half.size());
      t.edge_half.push_back(h);
      t.edge_of[h] = e;
      if (t.twin[h] != kNone) t.edge_of[t.twin[h]] = e;
    }
  }

  // Per vertex: its triangles, its boundary half-edges (at most one of each
  // direction when the triangles form a single fan), any outgoing half-edge.
  t.triangles_at.assign(vertex_count, 0);
  t.out_boundary.assign(vertex_count, kNone);
  t.in_boundary.assign(vertex_count, kNone);
  std::vector<uint32_t> any_out(vertex_count, kNone);
  for (uint32_t h = 0; h < H; ++h) {
    const uint32_t v = t.T[h];
    ++t.triangles_at[v];
    if (any_out[v] == kNone) any_out[v] = h;
    if (t.twin[h] == kNone) {
      if (t.out_boundary[v] != kNone) return "vertex with two boundary fans";
      t.out_boundary[v] = h;
      const uint32_t w = t.T[next(h)];
      if (t.in_boundary[w] != kNone) return "vertex with two boundary fans";
      t.in_boundary[w] = h;
    }
  }

  // Valence: triangles, plus one on the boundary.
  t.boundary.assign(vertex_count, 0);
  t.valence.assign(vertex_count, 0);
  for (uint32_t v = 0; v < vertex_count; ++v) {
    t.boundary[v] = t.out_boundary[v] != kNone;
    t.valence[v] = t.triangles_at[v] + t.boundary[v];
  }

  // Single fan: the counter-clockwise walk x -> twin(prev(x)) from the
  // boundary half-edge (or any outgoing half-edge of an interior vertex)
  // must visit every triangle of the vertex.
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (t.triangles_at[v] == 0) continue;
    const uint32_t start = t.boundary[v] ? t.out_boundary[v] : any_out[v];
    uint32_t visited = 1;
    for (uint32_t x = start;;) {
      const uint32_t y = t.twin[prev(x)];
      if (y == kNone || y == start) break;
      x = y;
      if (++visited > t.triangles_at[v]) break;
    }
    if (visited != t.triangles_at[v]) return "triangles around a vertex form more than one fan";
  }
  return {};
}

}  // namespace dbss_ref::detail
