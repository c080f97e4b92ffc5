// Small vector helpers and smoothing targets shared by the mesh repair files
// (mesh_folds.cpp, self_intersections.cpp, mesh_adjacency.cpp), tube_points.cpp and
// point_rims.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/mesh_adjacency.h"

namespace dbss::mesh_geometry {

using V3 = std::array<double, 3>;
inline V3 pos(const TriangleMesh& m, uint32_t v) { return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}; }
inline V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V3 cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
inline double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
// An undirected edge's key: the same for (a, b) and (b, a).
// A triangle's shape: 4 sqrt(3) area / (sum of squared edges); 1 when
// equilateral, 0 when flat or a point.
inline double quality(V3 a, V3 b, V3 c) {
  const double e = dot(sub(b, a), sub(b, a)) + dot(sub(c, b), sub(c, b)) + dot(sub(a, c), sub(a, c));
  if (!(e > 0)) return 0;
  const V3 n = cross(sub(b, a), sub(c, a));
  return 2 * std::sqrt(3.0) * std::sqrt(dot(n, n)) / e;
}
inline uint64_t edge_key(uint32_t a, uint32_t b) { return uint64_t{std::min(a, b)} << 32 | std::max(a, b); }
// The mean of v's neighbours' positions (false: v has none).
inline bool neighbour_mean(const TriangleMesh& m, const Adjacency& adj, uint32_t v, float out[3]) {
  const uint32_t deg = adj.offset[v + 1] - adj.offset[v];
  if (deg == 0) return false;
  double sum[3] = {0, 0, 0};
  for (uint32_t j = adj.offset[v]; j < adj.offset[v + 1]; ++j)
    for (int a = 0; a < 3; ++a) sum[a] += m.positions[3 * size_t{adj.index[j]} + a];
  for (int a = 0; a < 3; ++a) out[a] = static_cast<float>(sum[a] / deg);
  return true;
}
// Where smoothing takes v: its neighbours' mean, or on the boundary its two
// rim neighbours' mean (the mean of all would pull the rim into the sheet).
using Rim = std::vector<std::array<uint32_t, 2>>;
inline bool smoothing_target(const TriangleMesh& m, const Adjacency& adj, const Rim& rim, uint32_t v, float out[3]) {
  if (rim[v][0] == kNotOnRim) return neighbour_mean(m, adj, v, out);
  for (int a = 0; a < 3; ++a)
    out[a] = static_cast<float>(0.5 * (double{m.positions[3 * size_t{rim[v][0]} + a]} + m.positions[3 * size_t{rim[v][1]} + a]));
  return true;
}
inline V3 face_normal(const TriangleMesh& m, size_t f) {
  const V3 a = pos(m, m.triangles[3 * f]), b = pos(m, m.triangles[3 * f + 1]), c = pos(m, m.triangles[3 * f + 2]);
  return cross(sub(b, a), sub(c, a));
}

// Squared distance from p to the segment ab (ab of zero length: to a).
inline double distance2_to_segment(V3 p, V3 a, V3 b) {
  const V3 ab = sub(b, a), ap = sub(p, a);
  const double len2 = dot(ab, ab);
  double t = len2 > 0 ? dot(ap, ab) / len2 : 0;
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  double d2 = 0;
  for (int k = 0; k < 3; ++k) d2 += (ap[k] - t * ab[k]) * (ap[k] - t * ab[k]);
  return d2;
}

}  // namespace dbss::mesh_geometry
