#include "crease_slivers.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

namespace {

// c is on the segment u-w: within this share of its length from the line,
// and this far from either end (an apex near an end is a short edge, not a
// sliver).  At 0.02 no sliver was found: the crease vertices' snap onto the
// sides' planes, after the tags are chosen, leaves the apex up to a few
// hundredths off (bench/crease_bench.md, fourteenth session).
constexpr double kOnLine = 0.1, kFromEnd = 0.1;

V3 normal_of(const V3& a, const V3& b, const V3& c) { return cross(sub(b, a), sub(c, a)); }

}  // namespace

size_t flip_slivers(TriangleMesh& mesh, const LevelTopology& t, format::Creases& tags, std::vector<uint32_t>& count,
                    LevelTopology& flipped) {
  const uint32_t n = t.vertex_count;
  std::vector<uint8_t> boundary(n, 0);
  for (uint32_t h = 0; h < t.triangles.size(); ++h)
    if (t.twin[h] == kNoHalfEdge) boundary[t.triangles[h]] = 1, boundary[t.triangles[next_half(h)]] = 1;
  // Each vertex's triangles, for the fold check of c's move.
  std::vector<std::vector<uint32_t>> fan(n);
  for (uint32_t f = 0; f < t.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) fan[t.triangles[3 * f + k]].push_back(f);
  std::unordered_set<uint64_t> edges, tagged;
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t h = t.edge_half[e];
    edges.insert(edge_key(t.triangles[h], t.triangles[next_half(h)]));
    if (tags.edge[e]) tagged.insert(edge_key(t.triangles[h], t.triangles[next_half(h)]));
  }
  const std::vector<uint32_t> triangles = mesh.triangles;
  const std::vector<float> positions = mesh.positions;
  const std::vector<uint32_t> counts = count;
  std::vector<uint8_t> touched(t.triangle_count(), 0);
  size_t flips = 0;
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    if (!tags.edge[e]) continue;
    for (const uint32_t h : {t.edge_half[e], t.twin[t.edge_half[e]]}) {
      if (h == kNoHalfEdge || t.twin[h] == kNoHalfEdge) continue;
      const uint32_t tw = t.twin[h], f = h / 3, g = tw / 3;
      const uint32_t u = t.triangles[h], w = t.triangles[next_half(h)], c = t.triangles[prev_half(h)], d = t.triangles[prev_half(tw)];
      if (touched[f] || touched[g] || c == d || count[c] != 0 || tags.corner[c] || boundary[c] || edges.count(edge_key(c, d))) continue;
      // fan[] holds the triangles as they were before this pass: once an
      // earlier flip has rebuilt one of c's triangles (c was its far corner
      // d), the fold check below would read stale corners, so c waits.
      if (std::any_of(fan[c].begin(), fan[c].end(), [&](uint32_t x) { return touched[x] != 0; })) continue;
      const V3 pu = pos(mesh, u), pw = pos(mesh, w), pc = pos(mesh, c), pd = pos(mesh, d);
      const V3 uw = sub(pw, pu);
      const double l2 = dot(uw, uw);
      if (!(l2 > 0)) continue;
      const double s = dot(sub(pc, pu), uw) / l2;
      if (s < kFromEnd || s > 1 - kFromEnd) continue;
      const V3 on = {pu[0] + s * uw[0], pu[1] + s * uw[1], pu[2] + s * uw[2]};
      if (dot(sub(pc, on), sub(pc, on)) > kOnLine * kOnLine * l2) continue;
      // The new triangles (c, u, d) and (d, w, c) lie on d's side, turned as
      // (w, u, d) is; c's other triangles keep their orientation with c on
      // the line.
      const V3 side = normal_of(pw, pu, pd);
      if (!(dot(normal_of(on, pu, pd), side) > 0) || !(dot(normal_of(pd, pw, on), side) > 0)) continue;
      bool folds = false;
      for (uint32_t x : fan[c]) {
        if (x == f) continue;
        V3 p[3], q[3];
        for (int k = 0; k < 3; ++k) {
          const uint32_t v = t.triangles[3 * x + k];
          p[k] = pos(mesh, v), q[k] = v == c ? on : p[k];
        }
        const V3 before = normal_of(p[0], p[1], p[2]), after = normal_of(q[0], q[1], q[2]);
        folds = folds || !(dot(before, after) > 0);
      }
      if (folds) continue;
      for (int k = 0; k < 3; ++k) mesh.positions[3 * size_t{c} + k] = static_cast<float>(on[k]);
      mesh.triangles[3 * f] = c, mesh.triangles[3 * f + 1] = u, mesh.triangles[3 * f + 2] = d;
      mesh.triangles[3 * g] = d, mesh.triangles[3 * g + 1] = w, mesh.triangles[3 * g + 2] = c;
      edges.erase(edge_key(u, w)), edges.insert(edge_key(c, d));
      tagged.erase(edge_key(u, w)), tagged.insert(edge_key(u, c)), tagged.insert(edge_key(c, w));
      count[c] += 2;
      touched[f] = touched[g] = 1;
      ++flips;
      break;
    }
  }
  if (flips == 0) return 0;
  auto built = build_topology(n, mesh.triangles);
  if (!built.ok()) {  // not expected (c-d was no edge, so the mesh stays manifold): nothing flipped
    mesh.triangles = triangles, mesh.positions = positions, count = counts;
    return 0;
  }
  flipped = std::move(built).value();
  tags.edge.assign(flipped.edge_count(), 0);
  for (uint32_t e = 0; e < flipped.edge_count(); ++e) {
    const uint32_t h = flipped.edge_half[e];
    tags.edge[e] = tagged.count(edge_key(flipped.triangles[h], flipped.triangles[next_half(h)])) ? 1 : 0;
  }
  return flips;
}

}  // namespace dbss
