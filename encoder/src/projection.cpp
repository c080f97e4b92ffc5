#include "dbss/encoder/projection.h"

#include "dbss/encoder/mesh_ops.h"

namespace dbss {

size_t project_to_points(TriangleMesh& m, const PointIndex& index) {
  const PointCloud& pc = index.points();
  const Adjacency vt = vertex_triangles(m);
  size_t kept = 0;
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    float* p = &m.positions[3 * v];
    const uint32_t c = index.nearest(p);
    if (move_keeps_orientation(m, vt, static_cast<uint32_t>(v), &pc.xyz[3 * c])) {
      for (int a = 0; a < 3; ++a) p[a] = pc.xyz[3 * c + a];
    } else {
      ++kept;
    }
  }
  return kept;
}

}  // namespace dbss
