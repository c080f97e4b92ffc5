// Exact closest-surface distances through a bounding-volume hierarchy.
#include "dbss/encoder/triangle_tree.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace dbss {

namespace {
inline double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline void sub3(const double* a, const double* b, double* o) { o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2]; }
inline double dist2(const double* a, const double* b) {
  double d[3];
  sub3(a, b, d);
  return dot3(d, d);
}
// Squared distance from p to an axis-aligned box (0 inside).
inline double box_distance2(const double* p, const double* lo, const double* hi) {
  double s = 0;
  for (int a = 0; a < 3; ++a) {
    const double d = p[a] < lo[a] ? lo[a] - p[a] : (p[a] > hi[a] ? p[a] - hi[a] : 0.0);
    s += d * d;
  }
  return s;
}
constexpr uint32_t kLeafSize = 4;
}  // namespace

double point_triangle_distance2(const double p[3], const double a[3], const double b[3], const double c[3]) {
  // Voronoi regions of the triangle's corners, edges and face, in turn.
  double ab[3], ac[3], ap[3];
  sub3(b, a, ab), sub3(c, a, ac), sub3(p, a, ap);
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) return dist2(p, a);
  double bp[3];
  sub3(p, b, bp);
  const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dist2(p, b);
  double cp[3];
  sub3(p, c, cp);
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dist2(p, c);
  auto on_segment = [&](const double* s, const double* dir, double t) {
    const double x[3] = {s[0] + t * dir[0], s[1] + t * dir[1], s[2] + t * dir[2]};
    return dist2(p, x);
  };
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return on_segment(a, ab, d1 / (d1 - d3));
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return on_segment(a, ac, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    return on_segment(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) {
    // Degenerate (collinear corners) and not caught above: the closest of the
    // three edges.
    const double bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    auto seg = [&](const double* s, const double* dir) {
      const double l2 = dot3(dir, dir);
      double sp[3];
      sub3(p, s, sp);
      const double t = l2 > 0 ? std::clamp(dot3(sp, dir) / l2, 0.0, 1.0) : 0.0;
      return on_segment(s, dir, t);
    };
    return std::min({seg(a, ab), seg(a, ac), seg(b, bc)});
  }
  const double v = vb / sum, w = vc / sum;
  const double x[3] = {a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w};
  return dist2(p, x);
}

TriangleTree::TriangleTree(const TriangleMesh& m) {
  const size_t nf = m.triangle_count();
  if (nf == 0) return;
  std::vector<uint32_t> order(nf);
  std::iota(order.begin(), order.end(), 0u);
  std::vector<double> centroid(3 * nf);
  for (size_t f = 0; f < nf; ++f)
    for (int a = 0; a < 3; ++a)
      centroid[3 * f + a] = (double{m.positions[3 * size_t{m.triangles[3 * f]} + a]} +
                             m.positions[3 * size_t{m.triangles[3 * f + 1]} + a] +
                             m.positions[3 * size_t{m.triangles[3 * f + 2]} + a]) / 3;
  // Median splits along the longest axis of the centroids' bounds; nodes are
  // built in a work list so depth never touches the call stack.  The node
  // count is known in advance (a node of c > kLeafSize triangles has children
  // of c/2 and c - c/2, so each depth holds at most two sizes): reserving it
  // exactly keeps the vector from doubling while it is built, which on a
  // finest level was the process's memory peak (leaves hold 3-4 triangles,
  // so nf / kLeafSize under-counts by about 2x).
  size_t node_count = 0;
  for (std::vector<std::pair<size_t, size_t>> depth{{nf, 1}}; !depth.empty();) {
    std::vector<std::pair<size_t, size_t>> next;  // (size, how many), at most two entries
    const auto add = [&](size_t c, size_t times) {
      for (auto& e : next)
        if (e.first == c) return void(e.second += times);
      next.emplace_back(c, times);
    };
    for (const auto& [c, times] : depth) {
      node_count += times;
      if (c > kLeafSize) add(c / 2, times), add(c - c / 2, times);
    }
    depth = std::move(next);
  }
  nodes_.reserve(node_count);
  nodes_.push_back({{}, {}, 0, static_cast<uint32_t>(nf)});
  for (size_t i = 0; i < nodes_.size(); ++i) {
    const uint32_t first = nodes_[i].first, count = nodes_[i].count;
    Node& n = nodes_[i];
    for (int a = 0; a < 3; ++a) n.lo[a] = std::numeric_limits<double>::infinity(), n.hi[a] = -n.lo[a];
    double clo[3] = {n.lo[0], n.lo[1], n.lo[2]}, chi[3] = {n.hi[0], n.hi[1], n.hi[2]};
    for (uint32_t j = first; j < first + count; ++j) {
      const uint32_t f = order[j];
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) {
          const double x = m.positions[3 * size_t{m.triangles[3 * size_t{f} + k]} + a];
          n.lo[a] = std::min(n.lo[a], x), n.hi[a] = std::max(n.hi[a], x);
        }
      for (int a = 0; a < 3; ++a) clo[a] = std::min(clo[a], centroid[3 * f + a]), chi[a] = std::max(chi[a], centroid[3 * f + a]);
    }
    if (count <= kLeafSize) continue;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
    const uint32_t half = count / 2;
    std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                     [&](uint32_t x, uint32_t y) { return centroid[3 * x + axis] < centroid[3 * y + axis]; });
    const uint32_t child = static_cast<uint32_t>(nodes_.size());
    nodes_[i].first = child;
    nodes_[i].count = 0;
    nodes_.push_back({{}, {}, first, half});
    nodes_.push_back({{}, {}, first + half, count - half});
  }
  assert(nodes_.size() == node_count);
  corners_.resize(9 * nf);
  for (size_t j = 0; j < nf; ++j)
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) corners_[9 * j + 3 * k + a] = m.positions[3 * size_t{m.triangles[3 * size_t{order[j]} + k]} + a];
}

double TriangleTree::distance(const double p[3]) const {
  double best = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (box_distance2(p, n.lo, n.hi) >= best) continue;
    if (n.count > 0) {
      for (uint32_t j = n.first; j < n.first + n.count; ++j) {
        const double* t = &corners_[9 * size_t{j}];
        best = std::min(best, point_triangle_distance2(p, t, t + 3, t + 6));
      }
      continue;
    }
    // Nearer child last, so it is popped first and tightens `best` early.
    const Node& l = nodes_[n.first];
    const Node& r = nodes_[n.first + 1];
    const bool left_first = box_distance2(p, l.lo, l.hi) <= box_distance2(p, r.lo, r.hi);
    stack[top++] = left_first ? n.first + 1 : n.first;
    stack[top++] = left_first ? n.first : n.first + 1;
  }
  return std::sqrt(best);
}

}  // namespace dbss

namespace dbss {

namespace {
// The closest point of triangle abc to p (the same regions as
// point_triangle_distance2, returning the point).
void closest_on_triangle(const double p[3], const double a[3], const double b[3], const double c[3], double out[3]) {
  double ab[3], ac[3], ap[3];
  sub3(b, a, ab), sub3(c, a, ac), sub3(p, a, ap);
  auto set = [&](const double* s, const double* dir, double t) {
    for (int k = 0; k < 3; ++k) out[k] = s[k] + t * dir[k];
  };
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) return set(a, ab, 0);
  double bp[3];
  sub3(p, b, bp);
  const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return set(b, ab, 0);
  double cp[3];
  sub3(p, c, cp);
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return set(c, ab, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return set(a, ab, d1 / (d1 - d3));
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return set(a, ac, d2 / (d2 - d6));
  const double bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return set(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double sum = va + vb + vc;
  if (!(sum > 0)) {
    // Degenerate: the nearest of its three edges.
    out[0] = a[0], out[1] = a[1], out[2] = a[2];
    double best = std::numeric_limits<double>::infinity();
    using Seg = std::pair<const double*, const double*>;
    for (const auto& [s, dir] : {Seg{a, ab}, Seg{a, ac}, Seg{b, bc}}) {
      const double l2 = dot3(dir, dir);
      double sp[3], x[3];
      sub3(p, s, sp);
      const double t = l2 > 0 ? std::clamp(dot3(sp, dir) / l2, 0.0, 1.0) : 0.0;
      for (int k = 0; k < 3; ++k) x[k] = s[k] + t * dir[k];
      if (const double d = dist2(p, x); d < best) best = d, out[0] = x[0], out[1] = x[1], out[2] = x[2];
    }
    return;
  }
  const double v = vb / sum, w = vc / sum;
  for (int k = 0; k < 3; ++k) out[k] = a[k] + ab[k] * v + ac[k] * w;
}

// Slab test: the parameter interval of the line p + t dir inside the box,
// intersected with [lo_t, hi_t]; false when empty.
bool line_box(const double* p, const double* inv, const double* lo, const double* hi, double lo_t, double hi_t) {
  for (int a = 0; a < 3; ++a) {
    double t0 = (lo[a] - p[a]) * inv[a], t1 = (hi[a] - p[a]) * inv[a];
    if (std::isnan(t0) || std::isnan(t1)) {  // dir[a] == 0 with p on a slab plane
      if (p[a] < lo[a] || p[a] > hi[a]) return false;
      continue;
    }
    if (t0 > t1) std::swap(t0, t1);
    lo_t = std::max(lo_t, t0), hi_t = std::min(hi_t, t1);
    if (lo_t > hi_t) return false;
  }
  return true;
}
}  // namespace

double TriangleTree::closest_point(const double p[3], double out[3]) const {
  out[0] = p[0], out[1] = p[1], out[2] = p[2];
  double best = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (box_distance2(p, n.lo, n.hi) >= best) continue;
    if (n.count > 0) {
      for (uint32_t j = n.first; j < n.first + n.count; ++j) {
        const double* t = &corners_[9 * size_t{j}];
        double x[3] = {t[0], t[1], t[2]};
        closest_on_triangle(p, t, t + 3, t + 6, x);
        if (const double d = dist2(p, x); d < best) best = d, out[0] = x[0], out[1] = x[1], out[2] = x[2];
      }
      continue;
    }
    const Node& l = nodes_[n.first];
    const Node& r = nodes_[n.first + 1];
    const bool left_first = box_distance2(p, l.lo, l.hi) <= box_distance2(p, r.lo, r.hi);
    stack[top++] = left_first ? n.first + 1 : n.first;
    stack[top++] = left_first ? n.first : n.first + 1;
  }
  return std::sqrt(best);
}

bool TriangleTree::nearest_line_hit(const double p[3], const double dir[3], double limit, double& t_out) const {
  if (nodes_.empty()) return false;
  const double inv[3] = {1 / dir[0], 1 / dir[1], 1 / dir[2]};
  // Best facing hit and best hit of any facing, by |t|.
  double facing = std::numeric_limits<double>::infinity(), any = facing, t_facing = 0, t_any = 0;
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    // A facing hit is the answer once found; boxes farther than it cannot
    // improve it (a box only nearer than `any` could still hold a facing one).
    const double reach = std::min(limit, facing);
    if (!line_box(p, inv, n.lo, n.hi, -reach, reach)) continue;
    if (n.count > 0) {
      for (uint32_t j = n.first; j < n.first + n.count; ++j) {
        const double* a = &corners_[9 * size_t{j}];
        const double *b = a + 3, *c = a + 6;
        // Moller-Trumbore on the full line; barycentric bounds inclusive so
        // a line through an edge is not lost between two triangles.
        double e1[3], e2[3], h[3], s[3], q[3];
        sub3(b, a, e1), sub3(c, a, e2);
        h[0] = dir[1] * e2[2] - dir[2] * e2[1], h[1] = dir[2] * e2[0] - dir[0] * e2[2], h[2] = dir[0] * e2[1] - dir[1] * e2[0];
        const double det = dot3(e1, h);
        if (det == 0 || !std::isfinite(det)) continue;
        const double f = 1 / det;
        sub3(p, a, s);
        const double u = f * dot3(s, h);
        if (u < 0 || u > 1) continue;
        q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2], q[2] = s[0] * e1[1] - s[1] * e1[0];
        const double v = f * dot3(dir, q);
        if (v < 0 || u + v > 1) continue;
        const double t = f * dot3(e2, q);
        const double at = std::abs(t);
        if (at > limit) continue;
        // det = e1 . (dir x e2) = -dir . (e1 x e2): negative when the
        // triangle's normal faces along dir.
        if (det < 0 && at < facing) facing = at, t_facing = t;
        if (at < any) any = at, t_any = t;
      }
      continue;
    }
    stack[top++] = n.first;
    stack[top++] = n.first + 1;
  }
  if (facing <= limit) return t_out = t_facing, true;
  if (any <= limit) return t_out = t_any, true;
  return false;
}

}  // namespace dbss
