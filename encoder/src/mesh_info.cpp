#include <numeric>

#include "dbss/decoder/topology.h"
#include "dbss/encoder/shell_mesh.h"

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
  info.euler = int64_t{topo.vertex_count} - topo.edge_count() + topo.triangle_count();
  info.genus = (2 * int64_t{info.components} - info.euler) / 2;
  return info;
}

}  // namespace dbss
