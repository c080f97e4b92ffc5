#include "crease_shape.h"

#include <unordered_set>

#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

ShapeStats shape_tagged_mesh(TriangleMesh& mesh, const LevelTopology& t, format::Creases& tags, const std::vector<uint32_t>& count,
                             const PointIndex& points, LevelTopology& shaped) {
  ShapeLocks locks;
  locks.pinned.assign(t.vertex_count, 0);
  for (uint32_t v = 0; v < t.vertex_count; ++v) locks.pinned[v] = count[v] > 0 || (v < tags.corner.size() && tags.corner[v]);
  for (uint32_t e = 0; e < t.edge_count(); ++e)
    if (tags.edge[e]) locks.kept_edges.insert(edge_key(t.triangles[t.edge_half[e]], t.triangles[next_half(t.edge_half[e])]));
  const std::vector<uint32_t> triangles = mesh.triangles;
  const std::vector<float> positions = mesh.positions;
  ShapeOptions o;
  o.snap = true;
  const ShapeStats st = improve_shape(mesh, &points, o, locks);
  if (st.flips == 0) return st;
  auto built = build_topology(t.vertex_count, mesh.triangles);
  if (!built.ok()) {  // not expected (a flip never makes an edge twice): the mesh as it came
    mesh.triangles = triangles, mesh.positions = positions;
    ShapeStats none;
    none.before = none.after = st.before;
    return none;
  }
  shaped = std::move(built).value();
  tags.edge.assign(shaped.edge_count(), 0);
  for (uint32_t e = 0; e < shaped.edge_count(); ++e) {
    const uint32_t h = shaped.edge_half[e];
    tags.edge[e] = locks.kept_edges.count(edge_key(shaped.triangles[h], shaped.triangles[next_half(h)])) ? 1 : 0;
  }
  return st;
}

}  // namespace dbss
