#include "dbss/encoder/shrink_wrap.h"

#include <array>
#include <cmath>
#include <cstdint>

#include "dbss/encoder/mesh_adjacency.h"
#include "dbss/encoder/mesh_folds.h"
#include "dbss/encoder/point_grid.h"
#include "dbss/encoder/self_intersections.h"

namespace dbss {

namespace {
// The smoothing of a boundary vertex: towards the mean of its two rim
// neighbours only, since the mean of all its neighbours lies inside the
// sheet and would pull the rim in by about half an edge per iteration.
// While rounding, the full step flattens a staircase rim; after it only the
// part along the rim, so spacing evens out without the rim's curve (which a
// step to the chord's middle cuts) shrinking it.
void rim_smoothing(const TriangleMesh& m, const std::array<uint32_t, 2>& ends, const float* p, bool rounding, double lap[3]) {
  const float* a = &m.positions[3 * size_t{ends[0]}];
  const float* b = &m.positions[3 * size_t{ends[1]}];
  double t[3], tt = 0, lt = 0;
  for (int k = 0; k < 3; ++k) {
    lap[k] = 0.5 * (double{a[k]} + b[k]) - p[k];
    t[k] = double{b[k]} - a[k];
    tt += t[k] * t[k], lt += lap[k] * t[k];
  }
  if (rounding) return;
  // A pinched vertex (ends {v, v}) has t = 0 and stays.
  for (int k = 0; k < 3; ++k) lap[k] = tt > 0 ? lt / tt * t[k] : 0.0;
}
}  // namespace

ShrinkWrapStats shrink_wrap(TriangleMesh& m, const PointIndex& index, const ShrinkWrapOptions& o) {
  const Adjacency adj = vertex_adjacency(m);
  const size_t n = m.vertex_count();
  double mean_edge = 0;
  for (size_t v = 0; v < n; ++v)
    for (uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i) {
      const uint32_t w = adj.index[i];
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(m.positions[3 * v + a] - m.positions[3 * w + a], 2);
      mean_edge += std::sqrt(d2);
    }
  mean_edge /= std::max<size_t>(1, adj.index.size());

  ShrinkWrapStats stats;
  const Adjacency vt = vertex_triangles(m);
  const auto rim = rim_neighbours(m);
  // Every fourth iteration, and the last, undoes the moves that made
  // triangles cross since the last check, starting from the carved shell
  // (which has none), so the wrapped mesh has none either: the orientation
  // check per vertex cannot see two sheets of a thin part meeting.  (Every
  // iteration would be safer still but doubles the time.)
  std::vector<float> safe = m.positions;
  // Each vertex's nearest point (its slot in the grid below), the next
  // search's starting bound.  Any point gives the same answer (a search
  // keeps the nearest it meets, the first in the tree's order among
  // equals, and the bound only skips subtrees with nothing as near): the
  // first iteration starts from the previous vertex's, near by since the
  // shell numbers its vertices cell by cell, instead of a search from
  // scratch per vertex beforehand.
  constexpr uint32_t kNoHint = UINT32_MAX;
  std::vector<uint32_t> hint(n, kNoHint);
  // The warm-started searches on a grid of cells about an edge long (the
  // same answers as the tree's: PointGrid::nearest).
  const PointGrid grid(index, mean_edge);
  for (int it = 0; it < o.max_iterations; ++it) {
    const auto normals = vertex_normals(m);
    double moved = 0;
    // Gauss-Seidel: each vertex moves in turn, and a move that would turn a
    // triangle over is shortened (halved up to three times) or skipped.
    for (size_t v = 0; v < n; ++v) {
      const float* p = &m.positions[3 * v];
      // Projection: part of the way to the closest point.
      const uint32_t from = hint[v] != kNoHint ? hint[v] : v > 0 ? hint[v - 1] : kNoHint;
      const uint32_t c = hint[v] = from != kNoHint ? grid.nearest_slot(p, from) : grid.slot_of(index.nearest(p));
      const float* cp = grid.slot_xyz(c);
      double q[3];
      for (int a = 0; a < 3; ++a) q[a] = p[a] + o.step * (cp[a] - p[a]);
      // Smoothing: towards the neighbours' average within the tangent plane
      // only, so triangles even out without the mesh shrinking away.
      double avg[3] = {0, 0, 0};
      const uint32_t deg = std::max<uint32_t>(1, adj.offset[v + 1] - adj.offset[v]);
      for (uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i)
        for (int a = 0; a < 3; ++a) avg[a] += m.positions[3 * adj.index[i] + a];
      double lap[3];
      for (int a = 0; a < 3; ++a) lap[a] = avg[a] / deg - p[a];
      const auto& nv = normals[v];
      // The first iterations smooth fully: the voxel staircase has steps
      // that tangential relaxation alone would fold instead of flatten.
      const double along = it < o.rounding_iterations ? 0.0 : lap[0] * nv[0] + lap[1] * nv[1] + lap[2] * nv[2];
      if (rim[v][0] == kNotOnRim) {
        for (int a = 0; a < 3; ++a) q[a] += o.smoothing * (lap[a] - along * nv[a]);
      } else {
        rim_smoothing(m, rim[v], p, it < o.rounding_iterations, lap);
        for (int a = 0; a < 3; ++a) q[a] += o.smoothing * lap[a];
      }
      for (int tries = 0; tries < 4; ++tries) {
        const float to[3] = {static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2])};
        if (move_keeps_orientation(m, vt, static_cast<uint32_t>(v), to)) {
          double d2 = 0;
          for (int a = 0; a < 3; ++a) d2 += (to[a] - p[a]) * double(to[a] - p[a]);
          moved += std::sqrt(d2);
          for (int a = 0; a < 3; ++a) m.positions[3 * v + a] = to[a];
          break;
        }
        for (int a = 0; a < 3; ++a) q[a] = 0.5 * (q[a] + p[a]);
      }
    }
    stats.iterations = it + 1;
    const bool converged = moved / std::max<size_t>(1, n) < o.tolerance * mean_edge;
    if (converged || it % 4 == 3 || it + 1 == o.max_iterations) {
      stats.undone += undo_self_intersections(m, safe);
      safe = m.positions;
    }
    if (converged) break;
  }
  // `safe` is the state the loop left (its last pass always checks).
  stats.untangled = untangle_folds(m, adj, rim);
  // With no fold met nothing moved since the loop's last check, which left
  // no crossings: the search for them is skipped.  Otherwise only the
  // triangles the untangling moved can cross (on the bunny 35k, a search
  // of a few dozen triangles instead of 73k).
  if (stats.untangled > 0) stats.undone += undo_new_crossings(m, safe);
  double sum = 0, worst = 0;
  for (size_t v = 0; v < n; ++v) {
    const float* p = &m.positions[3 * v];
    // From the last iteration's nearest point: the same distance as a
    // search from scratch (which cost 4% of the bunny's control mesh).
    const float* cp = grid.slot_xyz(hint[v] != kNoHint ? grid.nearest_slot(p, hint[v]) : grid.slot_of(index.nearest(p)));
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += std::pow(cp[a] - p[a], 2);
    sum += std::sqrt(d2);
    worst = std::max(worst, std::sqrt(d2));
  }
  stats.mean_distance = sum / std::max<size_t>(1, n);
  stats.max_distance = worst;
  return stats;
}

}  // namespace dbss
