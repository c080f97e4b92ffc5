#include <numeric>

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

}  // namespace dbss
