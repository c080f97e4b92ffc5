#include "dbss/decoder/topology.h"

#include <algorithm>
#include <string>

namespace dbss {

namespace {

// Edge numbering and per-vertex tables shared by the base build and the
// refinement: edges in order of their first half-edge.
void number_edges(LevelTopology& t) {
  const uint32_t halves = static_cast<uint32_t>(t.triangles.size());
  t.edge_of.resize(halves);
  t.edge_half.clear();
  t.edge_half.reserve(halves / 2 + halves / 6 + 1);
  for (uint32_t h = 0; h < halves; ++h) {
    const uint32_t o = t.twin[h];
    if (o == kNoHalfEdge || o > h) {
      t.edge_of[h] = static_cast<uint32_t>(t.edge_half.size());
      t.edge_half.push_back(h);
    } else {
      t.edge_of[h] = t.edge_of[o];
    }
  }
}

}  // namespace

Result<LevelTopology> build_topology(uint32_t vertex_count, std::span<const uint32_t> triangles) {
  if (triangles.size() % 3 != 0 || triangles.empty())
    return Status(ErrorCode::bad_mesh, "mesh has no triangles or a partial triangle");
  if (triangles.size() >= kNoHalfEdge)
    return Status(ErrorCode::bad_mesh, "mesh has too many triangles");
  const uint32_t halves = static_cast<uint32_t>(triangles.size());
  LevelTopology t;
  t.vertex_count = vertex_count;
  t.triangles.assign(triangles.begin(), triangles.end());
  for (uint32_t h = 0; h < halves; h += 3) {
    const uint32_t a = t.triangles[h], b = t.triangles[h + 1], c = t.triangles[h + 2];
    if (a >= vertex_count || b >= vertex_count || c >= vertex_count)
      return Status(ErrorCode::bad_mesh, "triangle " + std::to_string(h / 3) + " names a vertex past " +
                                             std::to_string(vertex_count));
    if (a == b || b == c || c == a)
      return Status(ErrorCode::bad_mesh, "triangle " + std::to_string(h / 3) + " repeats a vertex");
  }

  // Pair half-edges by sorting them on their undirected key: a one-time cost
  // at level 0; finer levels get their twins from the split pattern.
  std::vector<uint64_t> keys(halves);
  for (uint32_t h = 0; h < halves; ++h) {
    const uint64_t a = t.triangles[h], b = t.triangles[next_half(h)];
    keys[h] = (std::min(a, b) << 32 | std::max(a, b));
  }
  std::vector<uint32_t> order(halves);
  for (uint32_t h = 0; h < halves; ++h) order[h] = h;
  std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return keys[x] < keys[y] || (keys[x] == keys[y] && x < y); });
  t.twin.assign(halves, kNoHalfEdge);
  for (uint32_t i = 0; i < halves;) {
    uint32_t j = i + 1;
    while (j < halves && keys[order[j]] == keys[order[i]]) ++j;
    const auto edge_name = [&] {
      return "edge " + std::to_string(keys[order[i]] >> 32) + "-" + std::to_string(keys[order[i]] & 0xFFFFFFFFu);
    };
    if (j - i > 2) return Status(ErrorCode::bad_mesh, edge_name() + " has " + std::to_string(j - i) + " triangles (non-manifold)");
    if (j - i == 2) {
      const uint32_t x = order[i], y = order[i + 1];
      if (t.triangles[x] == t.triangles[y])
        return Status(ErrorCode::bad_mesh, edge_name() + " is used twice in the same direction (inconsistent orientation)");
      t.twin[x] = y;
      t.twin[y] = x;
    }
    i = j;
  }
  number_edges(t);

  // Vertex fans: walk clockwise to the fan's start (or all the way round),
  // then count the fan counter-clockwise; a second fan shows as a shortfall.
  std::vector<uint32_t> corners(vertex_count, 0), any_out(vertex_count, kNoHalfEdge);
  for (uint32_t h = 0; h < halves; ++h) {
    ++corners[t.triangles[h]];
    any_out[t.triangles[h]] = h;
  }
  t.vertex_start.resize(vertex_count);
  t.vertex_valence.resize(vertex_count);
  t.vertex_boundary.resize(vertex_count);
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (corners[v] == 0) return Status(ErrorCode::bad_mesh, "vertex " + std::to_string(v) + " is on no triangle");
    uint32_t start = any_out[v];
    bool boundary = false;
    for (uint32_t steps = 0; steps < corners[v]; ++steps) {
      const uint32_t o = t.twin[start];
      if (o == kNoHalfEdge) {
        boundary = true;
        break;
      }
      start = next_half(o);  // clockwise
      if (start == any_out[v]) break;
    }
    uint32_t fan = 0;
    uint32_t h = start;
    do {
      ++fan;
      const uint32_t o = t.twin[prev_half(h)];
      if (o == kNoHalfEdge) break;
      h = o;  // counter-clockwise
    } while (h != start && fan <= corners[v]);
    if (fan != corners[v])
      return Status(ErrorCode::bad_mesh, "vertex " + std::to_string(v) + " joins " + std::to_string(corners[v]) +
                                             " triangles in more than one fan (non-manifold)");
    const uint32_t valence = fan + (boundary ? 1 : 0);
    if (valence > kMaxValence)
      return Status(ErrorCode::bad_mesh, "vertex " + std::to_string(v) + " has valence " + std::to_string(valence) +
                                             ", over " + std::to_string(kMaxValence));
    t.vertex_start[v] = start;
    t.vertex_valence[v] = static_cast<uint16_t>(valence);
    t.vertex_boundary[v] = boundary ? 1 : 0;
  }
  return t;
}

void refine_triangles(const LevelTopology& p, std::vector<uint32_t>& out) {
  const uint32_t faces = p.triangle_count();
  const uint32_t base = p.vertex_count;
  out.resize(size_t{faces} * 12);
  const uint32_t* tri = p.triangles.data();
  const uint32_t* eo = p.edge_of.data();
  uint32_t* o = out.data();
  for (uint32_t f = 0; f < faces; ++f, tri += 3, eo += 3, o += 12) {
    const uint32_t m0 = base + eo[0], m1 = base + eo[1], m2 = base + eo[2];
    o[0] = tri[0], o[1] = m0, o[2] = m2;
    o[3] = tri[1], o[4] = m1, o[5] = m0;
    o[6] = tri[2], o[7] = m2, o[8] = m1;
    o[9] = m0, o[10] = m1, o[11] = m2;
  }
}

LevelTopology refine_topology(const LevelTopology& p) {
  LevelTopology c;
  const uint32_t faces = p.triangle_count();
  c.vertex_count = p.vertex_count + p.edge_count();
  refine_triangles(p, c.triangles);

  // Child half-edges of parent triangle f (child k = 4f+k):
  //   child k, local 0: v_k -> m_k, first half of parent half-edge 3f+k
  //   child k, local 1: m_k -> m_{k+2}, twin of centre local k+2
  //   child k, local 2: m_{k+2} -> v_k, second half of parent half-edge 3f+k+2
  //   centre, local j: m_j -> m_{j+1}, twin of child j+1 local 1
  // The first half of parent h pairs with the second half of twin(h) = 3g+j,
  // which lies in child (g, j+1) at local 2.
  c.twin.resize(size_t{faces} * 12);
  uint32_t* tw = c.twin.data();
  for (uint32_t f = 0; f < faces; ++f) {
    const uint32_t cf = 12 * f;  // first child half-edge of f
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t ph = p.twin[3 * f + k];
      tw[cf + 3 * k + 0] = ph == kNoHalfEdge ? kNoHalfEdge : 12 * (ph / 3) + 3 * ((ph % 3 + 1) % 3) + 2;
      tw[cf + 3 * k + 1] = cf + 9 + (k + 2) % 3;
      const uint32_t pp = p.twin[3 * f + (k + 2) % 3];
      tw[cf + 3 * k + 2] = pp == kNoHalfEdge ? kNoHalfEdge : 12 * (pp / 3) + 3 * (pp % 3) + 0;
      tw[cf + 9 + k] = cf + 3 * ((k + 1) % 3) + 1;
    }
  }
  number_edges(c);

  // Even vertices keep valence and boundary flag; their start half-edge is
  // the first half of the parent start.  Odd vertices have valence 6, or 4
  // on a boundary edge where the fan starts at the outgoing boundary half
  // m_k -> v_{k+1} (child k+1, local 2).
  c.vertex_start.resize(c.vertex_count);
  c.vertex_valence.resize(c.vertex_count);
  c.vertex_boundary.resize(c.vertex_count);
  for (uint32_t v = 0; v < p.vertex_count; ++v) {
    const uint32_t h = p.vertex_start[v];
    c.vertex_start[v] = 12 * (h / 3) + 3 * (h % 3);
    c.vertex_valence[v] = p.vertex_valence[v];
    c.vertex_boundary[v] = p.vertex_boundary[v];
  }
  for (uint32_t e = 0; e < p.edge_count(); ++e) {
    const uint32_t h = p.edge_half[e];
    const uint32_t f = h / 3, k = h % 3;
    const uint32_t v = p.vertex_count + e;
    if (p.twin[h] == kNoHalfEdge) {
      c.vertex_start[v] = 12 * f + 3 * ((k + 1) % 3) + 2;
      c.vertex_valence[v] = 4;
      c.vertex_boundary[v] = 1;
    } else {
      c.vertex_start[v] = 12 * f + 3 * k + 1;
      c.vertex_valence[v] = 6;
      c.vertex_boundary[v] = 0;
    }
  }
  return c;
}

}  // namespace dbss
