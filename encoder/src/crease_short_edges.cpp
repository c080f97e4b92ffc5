#include "crease_short_edges.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

namespace {

// An edge this share of the longest edge at its ends is short: the
// anchor's overshooting short edges had rings of 11-45 of their lengths.
constexpr double kShort = 1.0 / 8;
constexpr double kTurn = 0.866;  // cos 30 degrees
constexpr double kSliver = 0.05;
constexpr uint32_t kValence = 10;

}  // namespace

size_t collapse_short_edges(TriangleMesh& mesh, const LevelTopology& t, format::Creases& tags, std::vector<uint32_t>& count,
                            LevelTopology& collapsed) {
  const uint32_t n = t.vertex_count;
  std::vector<uint8_t> boundary(n, 0);
  for (uint32_t h = 0; h < t.triangles.size(); ++h)
    if (t.twin[h] == kNoHalfEdge) boundary[t.triangles[h]] = 1, boundary[t.triangles[next_half(h)]] = 1;
  std::vector<std::vector<uint32_t>> fan(n), ring(n);
  for (uint32_t f = 0; f < t.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      fan[t.triangles[3 * f + k]].push_back(f);
      ring[t.triangles[3 * f + k]].push_back(t.triangles[3 * f + (k + 1) % 3]);
    }
  std::vector<double> longest(n, 0);
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[next_half(h)];
    const double l = std::sqrt(dot(sub(pos(mesh, u), pos(mesh, w)), sub(pos(mesh, u), pos(mesh, w))));
    longest[u] = std::max(longest[u], l), longest[w] = std::max(longest[w], l);
  }
  const auto sharp = [&](uint32_t v) { return count[v] > 0 || tags.corner[v] != 0; };
  std::unordered_set<uint64_t> tagged;
  for (uint32_t e = 0; e < t.edge_count(); ++e)
    if (tags.edge[e]) tagged.insert(edge_key(t.triangles[t.edge_half[e]], t.triangles[next_half(t.edge_half[e])]));
  // into[v]: the vertex v merges into (v itself when kept).
  std::vector<uint32_t> into(n);
  for (uint32_t v = 0; v < n; ++v) into[v] = v;
  std::vector<uint8_t> touched(n, 0), dead(t.triangle_count(), 0);
  // How well v's triangles (but the two at the edge to u) fare with v at
  // u: the worst quality, or -1 when one turns by kTurn or more.
  const auto judge = [&](uint32_t v, uint32_t u) {
    double worst = 1;
    const V3 pu = pos(mesh, u);
    for (uint32_t f : fan[v]) {
      const uint32_t* c = &t.triangles[3 * f];
      if (c[0] == u || c[1] == u || c[2] == u) continue;
      V3 p[3], q[3];
      for (int k = 0; k < 3; ++k) p[k] = pos(mesh, c[k]), q[k] = c[k] == v ? pu : p[k];
      const V3 a = cross(sub(p[1], p[0]), sub(p[2], p[0])), b = cross(sub(q[1], q[0]), sub(q[2], q[0]));
      const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b));
      if (!(la > 0) || !(lb > 0) || dot(a, b) < kTurn * la * lb) return -1.0;
      worst = std::min(worst, quality(q[0], q[1], q[2]));
    }
    return worst;
  };
  size_t collapses = 0;
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t h = t.edge_half[e], tw = t.twin[h];
    if (tw == kNoHalfEdge || tags.edge[e]) continue;
    const uint32_t a = t.triangles[h], b = t.triangles[next_half(h)];
    if (touched[a] || touched[b] || boundary[a] || boundary[b] || (sharp(a) && sharp(b))) continue;
    const double l = std::sqrt(dot(sub(pos(mesh, a), pos(mesh, b)), sub(pos(mesh, a), pos(mesh, b))));
    if (!(l < kShort * std::max(longest[a], longest[b]))) continue;
    // Manifold after: a and b share only the two far corners.
    const uint32_t c = t.triangles[prev_half(h)], d = t.triangles[prev_half(tw)];
    size_t shared = 0;
    for (uint32_t x : ring[a]) shared += std::find(ring[b].begin(), ring[b].end(), x) != ring[b].end();
    if (shared != 2 || c == d) continue;
    const uint32_t merged = static_cast<uint32_t>(ring[a].size() + ring[b].size() - 4);
    if (merged > std::max<uint32_t>(kValence, static_cast<uint32_t>(std::max(ring[a].size(), ring[b].size())))) continue;
    // The far corners keep valence 3 at least.
    if (ring[c].size() <= 3 || ring[d].size() <= 3) continue;
    // Which end goes: never a sharp one; else the one whose triangles fare better.
    const double qa = sharp(a) ? -1 : judge(a, b), qb = sharp(b) ? -1 : judge(b, a);
    if (!(std::max(qa, qb) >= kSliver)) continue;
    const uint32_t gone = qa >= qb ? a : b, kept = gone == a ? b : a;
    into[gone] = kept;
    dead[h / 3] = dead[tw / 3] = 1;
    for (uint32_t v : {a, b}) {
      touched[v] = 1;
      for (uint32_t x : ring[v]) touched[x] = 1;
    }
    ++collapses;
  }
  if (collapses == 0) return 0;
  // Renumber: the kept vertices in their order.
  std::vector<uint32_t> index(n, 0);
  uint32_t kept_count = 0;
  for (uint32_t v = 0; v < n; ++v)
    if (into[v] == v) index[v] = kept_count++;
  TriangleMesh out;
  out.positions.reserve(3 * size_t{kept_count});
  for (uint32_t v = 0; v < n; ++v)
    if (into[v] == v)
      for (int k = 0; k < 3; ++k) out.positions.push_back(mesh.positions[3 * size_t{v} + k]);
  for (uint32_t f = 0; f < t.triangle_count(); ++f)
    if (!dead[f])
      for (int k = 0; k < 3; ++k) out.triangles.push_back(index[into[t.triangles[3 * f + k]]]);
  auto built = build_topology(kept_count, out.triangles);
  if (!built.ok()) return 0;  // not expected (the link test above): nothing collapsed
  mesh.positions = std::move(out.positions), mesh.triangles = std::move(out.triangles);
  collapsed = std::move(built).value();
  std::vector<uint8_t> corner(kept_count, 0);
  std::vector<uint32_t> new_count(kept_count, 0);
  for (uint32_t v = 0; v < n; ++v)
    if (into[v] == v) corner[index[v]] = tags.corner[v], new_count[index[v]] = count[v];
  tags.corner = std::move(corner), count = std::move(new_count);
  tags.edge.assign(collapsed.edge_count(), 0);
  std::unordered_set<uint64_t> renamed;
  for (uint64_t k : tagged) renamed.insert(edge_key(index[static_cast<uint32_t>(k >> 32)], index[static_cast<uint32_t>(k)]));
  for (uint32_t e = 0; e < collapsed.edge_count(); ++e) {
    const uint32_t h = collapsed.edge_half[e];
    tags.edge[e] = renamed.count(edge_key(collapsed.triangles[h], collapsed.triangles[next_half(h)])) ? 1 : 0;
  }
  return collapses;
}

}  // namespace dbss
