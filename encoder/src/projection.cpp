#include "dbss/encoder/projection.h"

#include "dbss/encoder/mesh_adjacency.h"
#include "dbss/encoder/mesh_folds.h"
#include "dbss/encoder/point_distances.h"

namespace dbss {

namespace {
// The foot of p on the least-squares plane of its nearest points: a move
// along the surface normal only, for vertices whose jump onto a point would
// turn a triangle over (a jump has a tangential part the size of the point
// spacing, a lot next to a short edge).
bool foot_on_plane(const PointCloud& pc, const uint32_t* near, size_t found, const float p[3], float out[3]) {
  if (found < 3) return false;
  const PointPlane plane = fit_plane(pc, near, found);
  double off = 0;
  for (int a = 0; a < 3; ++a) off += (p[a] - plane.point[a]) * plane.normal[a];
  for (int a = 0; a < 3; ++a) out[a] = static_cast<float>(p[a] - off * plane.normal[a]);
  return true;
}
}  // namespace

size_t project_to_points(TriangleMesh& m, const PointIndex& index) {
  const PointCloud& pc = index.points();
  const Adjacency vt = vertex_triangles(m);
  size_t kept = 0;
  constexpr size_t kTries = 16;
  uint32_t near[kTries];
  float dist2[kTries];
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    const uint32_t vi = static_cast<uint32_t>(v);
    float* p = &m.positions[3 * v];
    const float old[3] = {p[0], p[1], p[2]};
    // A fold that is there already (from a neighbour) does not block a move.
    const bool folded_before = folded_around(m, vt, vi);
    // Moves the vertex to `to` unless that turns a triangle over or folds an
    // edge; says whether it moved.
    const auto try_move = [&](const float* to) {
      if (!move_keeps_orientation(m, vt, vi, to)) return false;
      for (int a = 0; a < 3; ++a) p[a] = to[a];
      if (folded_before || !folded_around(m, vt, vi)) return true;
      for (int a = 0; a < 3; ++a) p[a] = old[a];
      return false;
    };
    // The closest point whose use turns no triangle over: on thin parts the
    // very closest can lie on the far side.
    const size_t found = index.nearest_k(p, kTries, near, dist2);
    bool moved = false;
    for (size_t i = 0; i < found && !moved; ++i) moved = try_move(&pc.xyz[3 * near[i]]);
    if (moved) continue;
    // Failing that, onto the points' local plane; failing that too, part of
    // the way to the closest point.  Either leaves the vertex off the points.
    ++kept;
    float foot[3];
    if (foot_on_plane(pc, near, std::min<size_t>(found, 8), old, foot) && try_move(foot)) continue;
    for (float t = 0.5f; found > 0 && t > 0.05f; t *= 0.5f) {
      float to[3];
      for (int a = 0; a < 3; ++a) to[a] = old[a] + t * (pc.xyz[3 * near[0] + a] - old[a]);
      if (try_move(to)) break;
    }
  }
  return kept;
}

}  // namespace dbss
