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
  // The order is by key, then by half-edge: two stable counting sorts, by
  // the larger end and then by the smaller, give exactly std::sort's order
  // in linear time (a third of level 0's topology in the browser was the
  // comparison sort).
  std::vector<uint32_t> order(halves), by_max(halves), count(size_t{vertex_count} + 1);
  const auto counting_pass = [&](const uint32_t* from, uint32_t* to, auto end_of) {
    std::fill(count.begin(), count.end(), 0u);
    for (uint32_t i = 0; i < halves; ++i) ++count[end_of(keys[from ? from[i] : i]) + 1];
    for (uint32_t v = 0; v < vertex_count; ++v) count[v + 1] += count[v];
    for (uint32_t i = 0; i < halves; ++i) {
      const uint32_t h = from ? from[i] : i;
      to[count[end_of(keys[h])]++] = h;
    }
  };
  counting_pass(nullptr, by_max.data(), [](uint64_t k) { return static_cast<uint32_t>(k & 0xFFFFFFFFu); });
  counting_pass(by_max.data(), order.data(), [](uint64_t k) { return static_cast<uint32_t>(k >> 32); });
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

Status set_creases(LevelTopology& t, std::span<const uint8_t> edge, std::span<const uint8_t> corner) {
  if (edge.empty() && corner.empty()) return {};
  if (edge.size() != t.edge_count() || corner.size() != t.vertex_count)
    return Status(ErrorCode::bad_mesh, "crease tags for " + std::to_string(edge.size()) + " edges and " +
                                           std::to_string(corner.size()) + " vertices; the control mesh has " +
                                           std::to_string(t.edge_count()) + " and " + std::to_string(t.vertex_count));
  std::vector<uint8_t> creases(t.vertex_count, 0);  // crease edges per vertex (valence <= 64 fits)
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    if (!edge[e]) continue;
    const uint32_t h = t.edge_half[e];
    const uint32_t u = t.triangles[h], w = t.triangles[next_half(h)];
    // A boundary edge already follows the boundary rule: a crease bit there
    // would say nothing, so the spec forbids it (one file per meaning).
    if (t.twin[h] == kNoHalfEdge)
      return Status(ErrorCode::bad_mesh, "crease edge " + std::to_string(e) + " (" + std::to_string(u) + "-" +
                                             std::to_string(w) + ") is on the boundary");
    ++creases[u], ++creases[w];
  }
  t.edge_crease.assign(edge.begin(), edge.end());
  for (uint8_t& b : t.edge_crease) b = b ? 1 : 0;
  bool any = false;
  for (uint32_t v = 0; v < t.vertex_count; ++v) {
    uint8_t& kind = t.vertex_boundary[v];
    if (creases[v] == 0 && !corner[v]) continue;
    kind = static_cast<uint8_t>(kind | kVertexSharp);
    // The four-point rule along a crease needs one more crease vertex on
    // each side: anything but a plain interior crease vertex stops it.
    if (corner[v] || creases[v] != 2 || (kind & kVertexBoundary)) kind = static_cast<uint8_t>(kind | kVertexCreaseEnd);
    any = true;
  }
  if (!any) t.edge_crease.clear();  // no tag at all: decodes as 1.0
  return {};
}

}  // namespace dbss
