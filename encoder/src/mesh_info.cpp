#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

#include "dbss/decoder/topology.h"
#include "dbss/encoder/mesh_info.h"

namespace dbss {

MeshInfo mesh_info(const TriangleMesh& m) {
  MeshInfo info;
  auto t = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
  if (!t.ok()) {
    info.status = t.status();
    return info;
  }
  const LevelTopology& topo = t.value();
  info.manifold = true;
  info.closed = true;
  for (uint32_t h = 0; h < topo.twin.size(); ++h)
    if (topo.twin[h] == kNoHalfEdge) info.closed = false;
  // Components by union-find over triangle corners.
  std::vector<uint32_t> parent(topo.vertex_count);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (size_t h = 0; h < topo.triangles.size(); ++h) {
    const uint32_t a = find(topo.triangles[h]), b = find(topo.triangles[next_half(static_cast<uint32_t>(h))]);
    if (a != b) parent[a] = b;
  }
  for (uint32_t v = 0; v < topo.vertex_count; ++v) info.components += find(v) == v;
  // Boundary loops: build_topology leaves every vertex one fan, so a
  // boundary vertex starts and ends exactly one boundary edge and the
  // components of the boundary edges are whole loops.
  std::vector<uint8_t> on_rim(topo.vertex_count, 0);
  std::iota(parent.begin(), parent.end(), 0u);
  for (uint32_t h = 0; h < topo.twin.size(); ++h) {
    if (topo.twin[h] != kNoHalfEdge) continue;
    const uint32_t a = topo.triangles[h], b = topo.triangles[next_half(h)];
    on_rim[a] = on_rim[b] = 1;
    if (find(a) != find(b)) parent[find(a)] = find(b);
  }
  for (uint32_t v = 0; v < topo.vertex_count; ++v) info.boundary_loops += on_rim[v] && find(v) == v;
  info.euler = int64_t{topo.vertex_count} - topo.edge_count() + topo.triangle_count();
  // Per component 2 - 2g - b = euler; summed, the same with the totals.
  info.genus = (2 * int64_t{info.components} - info.euler - info.boundary_loops) / 2;
  return info;
}

MeshInfo mesh_counts(const TriangleMesh& m) {
  MeshInfo info;
  info.manifold = true;
  const size_t nv = m.vertex_count(), nt = m.triangle_count();
  std::vector<uint32_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto join = [&](uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[a] = b;
  };
  // Undirected edges as sorted (low, high) pairs: an edge used once is on
  // the boundary.
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(3 * nt);
  std::vector<uint8_t> used(nv, 0);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[3 * t + k], b = m.triangles[3 * t + (k + 1) % 3];
      used[a] = 1;
      edges.emplace_back(std::min(a, b), std::max(a, b));
      join(a, b);
    }
  std::sort(edges.begin(), edges.end());
  size_t distinct = 0;
  std::vector<std::pair<uint32_t, uint32_t>> rim;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    ++distinct;
    if (j - i == 1) rim.push_back(edges[i]);
    i = j;
  }
  size_t vertices = 0;
  for (uint32_t v = 0; v < nv; ++v)
    if (used[v]) ++vertices, info.components += find(v) == v;
  info.closed = rim.empty();
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<uint8_t> on_rim(nv, 0);
  for (const auto& [a, b] : rim) on_rim[a] = on_rim[b] = 1, join(a, b);
  for (uint32_t v = 0; v < nv; ++v) info.boundary_loops += on_rim[v] && find(v) == v;
  info.euler = static_cast<int64_t>(vertices) - static_cast<int64_t>(distinct) + static_cast<int64_t>(nt);
  info.genus = (2 * int64_t{info.components} - info.euler - info.boundary_loops) / 2;
  return info;
}

}  // namespace dbss
