#include "dbss/encoder/mesh_shape.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "dbss/encoder/mesh_adjacency.h"
#include "dbss/encoder/mesh_folds.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/self_intersections.h"
#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A valence flip may lower the worse triangle's quality, but not under this
// share of what it was: trading valence for a sliver is what the pass is
// against.
constexpr double kValenceFlipKeeps = 0.6;
// A quality flip must raise the worse triangle's quality by this factor
// (and so cannot cycle with another quality flip).
constexpr double kQualityFlipGain = 1.15;
// Quality flips only for triangles this poor: above it QEM's choice of
// diagonal, which follows the surface, is worth more than the shape.
constexpr double kQualityFlipBelow = 0.35;
// No flip takes a vertex over this valence (the target: the
// butterfly's extraordinary stencils grow and overshoot with it).
constexpr int kMaxValence = 10;

V3 unit(V3 v) {
  const double l = std::sqrt(dot(v, v));
  if (!(l > 0)) return {0, 0, 0};
  return {v[0] / l, v[1] / l, v[2] / l};
}

// Distance from q to the least-squares plane of its 8 nearest points.
double gap_to_points(const PointIndex& points, const V3& q) {
  constexpr size_t kNear = 8;
  uint32_t near[kNear];
  float dist2[kNear];
  const float f[3] = {static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2])};
  const size_t found = points.nearest_k(f, kNear, near, dist2);
  if (found < 3) return 0;
  const PointPlane plane = fit_plane(points.points(), near, found);
  double off = 0;
  for (int a = 0; a < 3; ++a) off += (q[a] - plane.point[a]) * plane.normal[a];
  return std::abs(off);
}

V3 midpoint(V3 a, V3 b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}; }

uint64_t key(uint32_t u, uint32_t v) { return (uint64_t{u} << 32) | v; }

// Directed edge -> its triangle, valences and the boundary, for flips.
struct FlipState {
  std::unordered_map<uint64_t, uint32_t> edge;  // (u, v) -> triangle holding u->v
  std::vector<int> valence;
  std::vector<uint8_t> boundary;

  explicit FlipState(const TriangleMesh& m) : valence(m.vertex_count(), 0), boundary(m.vertex_count(), 0) {
    edge.reserve(3 * m.triangle_count());
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) edge[key(m.triangles[3 * f + k], m.triangles[3 * f + (k + 1) % 3])] = f;
    for (const auto& [uv, f] : edge) {
      const uint32_t u = static_cast<uint32_t>(uv >> 32), v = static_cast<uint32_t>(uv);
      if (!edge.count(key(v, u))) boundary[u] = boundary[v] = 1;  // a boundary edge
      ++valence[u];                                                  // each undirected edge once per end...
      if (!edge.count(key(v, u))) ++valence[v];                      // ...a boundary edge has one direction only
    }
  }
  int excess(uint32_t v, int delta) const {
    const int d = valence[v] + delta - (boundary[v] ? 4 : 6);
    return d * d;
  }
};

uint32_t third(const TriangleMesh& m, uint32_t f, uint32_t u, uint32_t v) {
  for (int k = 0; k < 3; ++k) {
    const uint32_t w = m.triangles[3 * f + k];
    if (w != u && w != v) return w;
  }
  return u;
}

// Tries the flip of the edge a->b of triangle f; says whether it was made.
// `points` (may be null) with `slack`: see ShapeOptions::flip_slack.
bool try_flip(TriangleMesh& m, FlipState& s, uint32_t f, uint32_t a, uint32_t b, double cos_bend, const PointIndex* points,
              double slack, const ShapeLocks* locks) {
  const auto twin = s.edge.find(key(b, a));
  if (twin == s.edge.end()) return false;  // a boundary edge
  if (locks != nullptr && locks->kept_edges.count(edge_key(a, b))) return false;
  const uint32_t g = twin->second;
  const uint32_t c = third(m, f, a, b), d = third(m, g, a, b);
  if (c == d || s.edge.count(key(c, d)) || s.edge.count(key(d, c))) return false;  // would be a second c-d edge
  if (s.valence[a] <= 3 || s.valence[b] <= 3) return false;
  if (std::max(s.valence[c], s.valence[d]) >= kMaxValence) return false;
  const V3 pa = pos(m, a), pb = pos(m, b), pc = pos(m, c), pd = pos(m, d);
  const V3 n1 = unit(cross(sub(pb, pa), sub(pc, pa))), n2 = unit(cross(sub(pa, pb), sub(pd, pb)));
  const V3 m1 = unit(cross(sub(pd, pa), sub(pc, pa))), m2 = unit(cross(sub(pb, pd), sub(pc, pd)));
  // The quad must be about flat before and after, and neither new triangle
  // may face away from it (a flip across a concave corner of the quad
  // would overlap its neighbour).
  if (dot(n1, n2) < cos_bend || dot(m1, m2) < cos_bend) return false;
  const V3 mean = unit({n1[0] + n2[0], n1[1] + n2[1], n1[2] + n2[2]});
  if (dot(m1, mean) < cos_bend || dot(m2, mean) < cos_bend) return false;
  const double q_old = std::min(quality(pa, pb, pc), quality(pb, pa, pd));
  const double q_new = std::min(quality(pa, pd, pc), quality(pd, pb, pc));
  const int e_old = s.excess(a, 0) + s.excess(b, 0) + s.excess(c, 0) + s.excess(d, 0);
  const int e_new = s.excess(a, -1) + s.excess(b, -1) + s.excess(c, 1) + s.excess(d, 1);
  const bool valence_flip = e_new < e_old && q_new >= kValenceFlipKeeps * q_old;
  const bool quality_flip = q_old < kQualityFlipBelow && q_new > kQualityFlipGain * q_old && e_new <= e_old + 2;
  if (!valence_flip && !quality_flip) return false;
  if (locks != nullptr && !locks->beside.empty()) {
    const uint8_t most = std::max(std::max(locks->beside[a], locks->beside[b]), std::max(locks->beside[c], locks->beside[d]));
    if (most >= 2 || (most == 1 && q_new < q_old)) return false;
  }
  if (points != nullptr && gap_to_points(*points, midpoint(pc, pd)) > gap_to_points(*points, midpoint(pa, pb)) + slack)
    return false;
  // a->b->c and b->a->d become a->d->c and d->b->c.
  const uint32_t t1[3] = {a, d, c}, t2[3] = {d, b, c};
  for (int k = 0; k < 3; ++k) m.triangles[3 * size_t{f} + k] = t1[k], m.triangles[3 * size_t{g} + k] = t2[k];
  s.edge.erase(key(a, b));
  s.edge.erase(key(b, a));
  s.edge[key(a, d)] = f;
  s.edge[key(d, c)] = f;
  s.edge[key(c, a)] = f;
  s.edge[key(d, b)] = g;
  s.edge[key(b, c)] = g;
  s.edge[key(c, d)] = g;
  --s.valence[a], --s.valence[b], ++s.valence[c], ++s.valence[d];
  return true;
}

size_t flip_pass(TriangleMesh& m, double cos_bend, const PointIndex* points, double slack, const ShapeLocks* locks) {
  FlipState s(m);
  size_t flips = 0;
  // Until no flip is left (each valence flip lowers an integer energy, each
  // quality flip raises a quality by a fixed factor), at most a few sweeps.
  for (int sweep = 0; sweep < 8; ++sweep) {
    size_t now = 0;
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = m.triangles[3 * size_t{f} + k], b = m.triangles[3 * size_t{f} + (k + 1) % 3];
        if (a < b && try_flip(m, s, f, a, b, cos_bend, points, slack, locks)) {
          ++now;
          break;  // triangle f changed: its other edges on the next sweep
        }
      }
    flips += now;
    if (now == 0) break;
  }
  return flips;
}

// The worst quality of the triangles around v.
double fan_quality(const TriangleMesh& m, const Adjacency& vt, uint32_t v) {
  double q = 1;
  for (uint32_t j = vt.offset[v]; j < vt.offset[v + 1]; ++j) q = std::min(q, triangle_quality(m, vt.index[j]));
  return q;
}

// `snap`: the vertices move only onto points (see ShapeOptions::snap).
size_t relax_pass(TriangleMesh& m, const PointIndex* points, double cos_bend, double relax_below, bool snap, const ShapeLocks* locks) {
  const Adjacency vt = vertex_triangles(m);
  const Adjacency adj = vertex_adjacency(m);
  const Rim rim = rim_neighbours(m);
  std::vector<uint8_t> wanted(m.vertex_count(), 0);
  for (size_t f = 0; f < m.triangle_count(); ++f)
    if (triangle_quality(m, f) < relax_below)
      for (int k = 0; k < 3; ++k) wanted[m.triangles[3 * f + k]] = 1;
  size_t moves = 0;
  constexpr size_t kNear = 8;
  uint32_t near[kNear];
  float dist2[kNear];
  for (uint32_t v = 0; v < m.vertex_count(); ++v) {
    if (!wanted[v] || rim[v][0] != kNotOnRim || vt.offset[v + 1] == vt.offset[v]) continue;
    if (locks != nullptr && v < locks->pinned.size() && locks->pinned[v]) continue;
    // The vertex's normal, and whether it sits on a sharp feature (its
    // triangles bend away from that normal).
    V3 n = {0, 0, 0};
    for (uint32_t j = vt.offset[v]; j < vt.offset[v + 1]; ++j) {
      const V3 fn = face_normal(m, vt.index[j]);
      for (int a = 0; a < 3; ++a) n[a] += fn[a];
    }
    n = unit(n);
    bool sharp = false;
    for (uint32_t j = vt.offset[v]; j < vt.offset[v + 1] && !sharp; ++j)
      sharp = dot(unit(face_normal(m, vt.index[j])), n) < cos_bend;
    if (sharp) continue;
    float mean[3];
    if (!neighbour_mean(m, adj, v, mean)) continue;
    float* p = &m.positions[3 * size_t{v}];
    V3 step = {0.5 * (mean[0] - p[0]), 0.5 * (mean[1] - p[1]), 0.5 * (mean[2] - p[2])};
    const double along = dot(step, n);
    for (int a = 0; a < 3; ++a) step[a] -= along * n[a];
    float to[3];
    for (int a = 0; a < 3; ++a) to[a] = static_cast<float>(p[a] + step[a]);
    bool on_points = snap;
    if (points != nullptr && !snap) {
      // Back onto the surface of the points: the tangent plane of a curved
      // surface leaves it by the square of the step.  Where the points'
      // plane leans away from the mesh (next to a thin part's rim, whose
      // points join the fit) it is no surface: onto a point instead (on the
      // thin plate of the tests the plane had doubled level 0's error).
      const size_t found = points->nearest_k(to, kNear, near, dist2);
      if (found >= 3) {
        const PointPlane plane = fit_plane(points->points(), near, found);
        double off = 0;
        for (int a = 0; a < 3; ++a) off += (to[a] - plane.point[a]) * plane.normal[a];
        if (std::abs(dot(plane.normal, n)) < cos_bend) on_points = true;
        else
          for (int a = 0; a < 3; ++a) to[a] = static_cast<float>(to[a] - off * plane.normal[a]);
      }
    }
    if (on_points && points != nullptr) {
      // Onto the point near the target that gives the fan its best worst
      // triangle, if that beats where the vertex is: it stays on the points.
      const size_t found = points->nearest_k(to, kNear, near, dist2);
      const float old[3] = {p[0], p[1], p[2]};
      double best = fan_quality(m, vt, v);
      size_t chosen = found;
      for (size_t i = 0; i < found; ++i) {
        const float* q = &points->points().xyz[3 * size_t{near[i]}];
        if (!move_keeps_orientation(m, vt, v, q)) continue;
        for (int a = 0; a < 3; ++a) p[a] = q[a];
        const double fq = fan_quality(m, vt, v);
        if (fq > best && !folded_around(m, vt, v)) best = fq, chosen = i;
        for (int a = 0; a < 3; ++a) p[a] = old[a];
      }
      if (chosen == found) continue;
      for (int a = 0; a < 3; ++a) p[a] = points->points().xyz[3 * size_t{near[chosen]} + a];
      ++moves;
      continue;
    }
    if (!move_keeps_orientation(m, vt, v, to)) continue;
    const bool folded_before = folded_around(m, vt, v);
    const float old[3] = {p[0], p[1], p[2]};
    for (int a = 0; a < 3; ++a) p[a] = to[a];
    if (!folded_before && folded_around(m, vt, v)) {
      for (int a = 0; a < 3; ++a) p[a] = old[a];
      continue;
    }
    ++moves;
  }
  return moves;
}

}  // namespace

double triangle_quality(const TriangleMesh& m, size_t f) {
  return quality(pos(m, m.triangles[3 * f]), pos(m, m.triangles[3 * f + 1]), pos(m, m.triangles[3 * f + 2]));
}

MeshShape mesh_shape(const TriangleMesh& m) {
  MeshShape s;
  if (m.triangle_count() == 0) return s;
  size_t poor = 0;
  s.min_quality = 1;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const double q = triangle_quality(m, f);
    poor += q < kPoorQuality;
    s.min_quality = std::min(s.min_quality, q);
  }
  s.poor_share = static_cast<double>(poor) / static_cast<double>(m.triangle_count());
  const Adjacency adj = vertex_adjacency(m);
  for (size_t v = 0; v < m.vertex_count(); ++v) s.max_valence = std::max(s.max_valence, adj.offset[v + 1] - adj.offset[v]);
  return s;
}

ShapeStats improve_shape(TriangleMesh& m, const PointIndex* points, const ShapeOptions& o) {
  return improve_shape(m, points, o, ShapeLocks{});
}

ShapeStats improve_shape(TriangleMesh& m, const PointIndex* points, const ShapeOptions& o, const ShapeLocks& locks) {
  const ShapeLocks* lk = locks.pinned.empty() && locks.kept_edges.empty() && locks.beside.empty() ? nullptr : &locks;
  ShapeStats st;
  st.before = mesh_shape(m);
  if (o.enabled && m.triangle_count() > 0) {
    const double cos_bend = std::cos(o.max_bend * kPi / 180);
    const double cos_flip = std::cos((points != nullptr ? o.flip_bend : o.max_bend) * kPi / 180);
    const size_t crossings = count_self_intersections(m);
    const double slack = points != nullptr ? o.flip_slack * point_spacing(*points, 1, 0.5) : 0;
    for (int r = 0; r < o.rounds; ++r) {
      const TriangleMesh saved = m;
      const size_t flips = flip_pass(m, cos_flip, points, slack, lk);
      const size_t moves = relax_pass(m, points, cos_bend, o.relax_below, o.snap, lk);
      if (count_self_intersections(m) > crossings) {
        m = saved;
        ++st.rounds_undone;
        break;
      }
      st.flips += flips;
      st.moves += moves;
      if (flips == 0 && moves == 0) break;
    }
  }
  st.after = mesh_shape(m);
  return st;
}

}  // namespace dbss
