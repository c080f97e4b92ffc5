#include "dbss/encoder/hole_bridge.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "dbss/encoder/self_intersections.h"

namespace dbss {

namespace {

using V3 = std::array<double, 3>;

// Largest mean LoopShape::wall of a pair of loops taken for a tube's ends.
constexpr double kMaxWall = 0.55;
// Smallest cosine between the gap and a loop's axis for the loop to face
// the other (axes within 66 degrees of the gap).  At 0.5 a triple torus cut
// at 15% lost a handle on the hole sweep (0.48); 0.4 changed no other case.
constexpr double kMinFacing = 0.4;
// Largest mean wall of a pair reported as possibly a cut tube (hole sweep:
// a junction's loop and its partner 0.58; holes in walls 0.8 and more).
constexpr double kMaxDoubtfulWall = 0.7;


V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double len(V3 a) { return std::sqrt(dot(a, a)); }

struct LoopShape {
  V3 centre{};
  V3 axis{};          // unit Newell normal of the walk: points away from the hole, into the surface it bounds
  double radius = 0;  // mean distance of the loop's vertices from the centre
  // Mean |cos| between the surface's normals at the loop's vertices and
  // the axis: near 0 where the surface round the loop runs along the axis
  // (the wall of a tube, cut across), near 1 where it lies across it (a
  // hole in a wall).
  double wall = 0;
  std::vector<double> param;  // arc length of each vertex from the first, over the perimeter: [0, 1)
};

V3 vertex(const TriangleMesh& m, uint32_t v) {
  return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
}

LoopShape shape_of(const TriangleMesh& m, const std::vector<uint32_t>& loop) {
  LoopShape s;
  const size_t n = loop.size();
  for (uint32_t v : loop)
    for (int a = 0; a < 3; ++a) s.centre[a] += m.positions[3 * v + a] / static_cast<double>(n);
  V3 newell{};
  double perimeter = 0;
  s.param.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const V3 p = sub(vertex(m, loop[i]), s.centre), q = sub(vertex(m, loop[(i + 1) % n]), s.centre);
    newell[0] += p[1] * q[2] - p[2] * q[1];
    newell[1] += p[2] * q[0] - p[0] * q[2];
    newell[2] += p[0] * q[1] - p[1] * q[0];
    s.radius += len(p) / static_cast<double>(n);
    s.param[i] = perimeter;
    perimeter += len(sub(q, p));
  }
  const double l = len(newell);
  if (l > 0)
    for (int a = 0; a < 3; ++a) s.axis[a] = newell[a] / l;
  for (double& t : s.param) t = perimeter > 0 ? t / perimeter : 0;
  return s;
}

// The point at arc-length parameter t (any real; taken modulo 1) along a
// closed polyline whose vertices sit at `param`.
V3 at(const TriangleMesh& m, const std::vector<uint32_t>& loop, const std::vector<double>& param, double t) {
  t -= std::floor(t);
  const size_t n = loop.size();
  size_t i = static_cast<size_t>(std::upper_bound(param.begin(), param.end(), t) - param.begin()) - 1;
  const double t0 = param[i], t1 = i + 1 < n ? param[i + 1] : 1.0;
  const double f = t1 > t0 ? (t - t0) / (t1 - t0) : 0;
  const V3 a = vertex(m, loop[i]), b = vertex(m, loop[(i + 1) % n]);
  return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
}

// The rings inherit the zigzag of the cut ends they are blended from.
// Taubin's smoothing round each ring (a shrinking step, then an inflating
// one) takes the zigzag out without shrinking the ring or touching the
// tube's bend, which a smoothing across rings, or a fairing, pulls straight
// (a torus cut through 60 degrees: Hermite rings 0.013 off the torus, after
// 20 fairing steps 0.15).
void smooth_ring(std::vector<V3>& ring) {
  constexpr double kLambda = 0.5, kMu = -0.53;
  constexpr int kRounds = 5;
  const size_t n = ring.size();
  std::vector<V3> next(n);
  for (int r = 0; r < 2 * kRounds; ++r) {
    const double f = r % 2 ? kMu : kLambda;
    for (size_t k = 0; k < n; ++k)
      for (int c = 0; c < 3; ++c)
        next[k][c] = ring[k][c] + f * (0.5 * (ring[(k + n - 1) % n][c] + ring[(k + 1) % n][c]) - ring[k][c]);
    ring.swap(next);
  }
}

// Triangulates the band between two closed polylines running the same way
// round, p below q, each starting at its vertex 0, the vertices at
// parameters tp and tq in [0, 1) on a common scale (tp[0] = tq[0] = 0
// roughly): the two are merged in parameter order, which jagged cut ends
// do not mislead as a shortest-diagonal rule is.  The triangles take p's
// edges backwards and q's forwards, so p may be a boundary walk (the
// surface on its left) and q the reverse of one, or a ring inside the tube.
void zip(TriangleMesh& m, const std::vector<uint32_t>& p, const std::vector<double>& tp, const std::vector<uint32_t>& q,
         const std::vector<double>& tq) {
  const size_t n = p.size(), k = q.size();
  size_t i = 0, j = 0;
  const auto next = [](const std::vector<double>& t, size_t i) { return i + 1 < t.size() ? t[i + 1] : 1.0 + t[0]; };
  while (i < n || j < k) {
    const uint32_t pi = p[i % n], qj = q[j % k];
    const bool advance_p = j == k || (i < n && next(tp, i) <= next(tq, j));
    if (advance_p) {
      m.triangles.insert(m.triangles.end(), {p[(i + 1) % n], pi, qj});
      ++i;
    } else {
      m.triangles.insert(m.triangles.end(), {qj, q[(j + 1) % k], pi});
      ++j;
    }
  }
}

// The walk of `loop` reversed and rotated to start at the vertex whose
// parameter (shifted by `offset`) is least, with the shifted parameters.
std::pair<std::vector<uint32_t>, std::vector<double>> reversed_from(const std::vector<uint32_t>& loop,
                                                                    const std::vector<double>& param, double offset) {
  const size_t n = loop.size();
  std::vector<uint32_t> r(n);
  std::vector<double> t(n);
  for (size_t i = 0; i < n; ++i) {
    r[i] = loop[(n - i) % n];
    const double u = 1.0 - param[(n - i) % n] - offset;
    t[i] = u - std::floor(u);
  }
  const size_t first = static_cast<size_t>(std::min_element(t.begin(), t.end()) - t.begin());
  std::rotate(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(first), r.end());
  std::rotate(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(first), t.end());
  return {r, t};
}

}  // namespace

size_t bridge_facing_loops(TriangleMesh& m, std::vector<std::vector<uint32_t>>& loops, double edge,
                           std::vector<uint32_t>& added, size_t* unbridged_pairs) {
  const size_t nl = loops.size();
  if (nl < 2 || edge <= 0) return 0;
  std::vector<LoopShape> shapes;
  for (const auto& l : loops) shapes.push_back(shape_of(m, l));
  {
    std::vector<V3> normal(m.vertex_count(), V3{0, 0, 0});  // area-weighted, unnormalized
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const V3 a = vertex(m, m.triangles[3 * t]);
      const V3 u = sub(vertex(m, m.triangles[3 * t + 1]), a), w = sub(vertex(m, m.triangles[3 * t + 2]), a);
      const V3 n{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) normal[m.triangles[3 * t + k]][c] += n[c];
    }
    for (size_t l = 0; l < nl; ++l) {
      for (uint32_t v : loops[l])
        if (const double ln = len(normal[v]); ln > 0) shapes[l].wall += std::abs(dot(normal[v], shapes[l].axis)) / ln;
      shapes[l].wall /= static_cast<double>(loops[l].size());
    }
  }
  // Candidate pairs, nearest (relative to their size) first.  The axis of a
  // walk with the surface on its left points into the tube it ends (away
  // from the gap), so across a gap the two axes point apart: the direction
  // from a to b runs against a's axis and along b's.  Two holes on the two
  // sides of a plate have axes pointing at each other instead.
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  // Pairs that look half like a tube's ends (one end faces the other, the
  // walls lean along the axes) but are not bridged: a cut handle whose end
  // lies in a junction, or a tube that would cross the mesh.  Capped, they
  // may cost a genus; the caller says so.
  std::vector<std::pair<size_t, size_t>> doubtful;
  for (size_t a = 0; a < nl; ++a)
    for (size_t b = a + 1; b < nl; ++b) {
      const LoopShape &sa = shapes[a], &sb = shapes[b];
      const V3 d = sub(sb.centre, sa.centre);
      const double gap = len(d);
      const double big = std::max(sa.radius, sb.radius), small = std::min(sa.radius, sb.radius);
      if (gap <= 0 || small < 0.5 * big || gap > 5 * big) continue;
      const V3 u{d[0] / gap, d[1] / gap, d[2] / gap};
      const bool a_faces = dot(u, sa.axis) < -kMinFacing, b_faces = dot(u, sb.axis) > kMinFacing;
      // Doubtful: one faces the other, and the other at least does not turn
      // its back (its axis within 120 degrees of the gap's direction).
      const bool half_facing = (a_faces && dot(u, sb.axis) > -0.5) || (b_faces && dot(u, sa.axis) < 0.5);
      if (half_facing && 0.5 * (sa.wall + sb.wall) < kMaxDoubtfulWall) doubtful.emplace_back(a, b);
      if (!a_faces || !b_faces) continue;
      // Ends of a tube, not holes in walls facing each other across a
      // ring's hole (where a shrink-wrap left the points): a pair of those
      // measured 0.585 (a handle too many), pairs of cut tubes' ends
      // 0.39-0.44; at 0.5 five of those were lost on the hole sweep, at
      // 0.55 three.
      if (0.5 * (sa.wall + sb.wall) > kMaxWall) continue;
      pairs.emplace_back(gap / (sa.radius + sb.radius), a, b);
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<uint8_t> used(nl, 0);
  size_t built = 0;
  size_t crossings = pairs.empty() ? 0 : count_self_intersections(m);
  for (const auto& [score, a, b] : pairs) {
    if (used[a] || used[b]) continue;
    const LoopShape &sa = shapes[a], &sb = shapes[b];
    const std::vector<uint32_t>&la = loops[a], &lb = loops[b];
    // b walked backwards runs round the tube the way a does; the offset that
    // lines the two up best keeps the tube from twisting.
    const auto back = [&](double t) { return at(m, lb, sb.param, 1.0 - t); };
    double offset = 0, best = 1e300;
    constexpr int kSamples = 64;
    for (int o = 0; o < kSamples; ++o) {
      double cost = 0;
      for (int k = 0; k < kSamples; ++k) {
        const V3 d = sub(at(m, la, sa.param, static_cast<double>(k) / kSamples),
                         back(static_cast<double>(k) / kSamples + static_cast<double>(o) / kSamples));
        cost += dot(d, d);
      }
      if (cost < best) best = cost, offset = static_cast<double>(o) / kSamples;
    }
    const double gap = len(sub(sb.centre, sa.centre));
    const int rings = std::clamp(static_cast<int>(std::lround(gap / (2 * edge))) - 1, 0, 64);
    const size_t count = std::max(la.size(), lb.size());
    const size_t added_before = added.size();
    const TriangleMesh before = m;
    // Rings on Hermite curves from each point of a to its partner on b,
    // leaving a against a's axis and entering b along b's: the tube bends
    // as the surface it continues does.
    std::vector<uint32_t> lower = la;
    std::vector<double> lower_param = sa.param, ring_param(count);
    for (size_t k = 0; k < count; ++k) ring_param[k] = static_cast<double>(k) / static_cast<double>(count);
    for (int r = 1; r <= rings; ++r) {
      const double t = static_cast<double>(r) / (rings + 1);
      const double h00 = 2 * t * t * t - 3 * t * t + 1, h10 = t * t * t - 2 * t * t + t;
      const double h01 = -2 * t * t * t + 3 * t * t, h11 = t * t * t - t * t;
      std::vector<V3> at_ring(count);
      for (size_t k = 0; k < count; ++k) {
        const double s = static_cast<double>(k) / static_cast<double>(count);
        const V3 pa = at(m, la, sa.param, s), pb = back(s + offset);
        // Tangents as long as this point's own chord: round a bend the
        // outer side's chord is the longer, and so is its arc.
        const double chord = len(sub(pb, pa));
        for (int c = 0; c < 3; ++c)
          at_ring[k][c] = h00 * pa[c] - h10 * chord * sa.axis[c] + h01 * pb[c] + h11 * chord * sb.axis[c];
      }
      smooth_ring(at_ring);
      std::vector<uint32_t> ring(count);
      for (size_t k = 0; k < count; ++k) {
        ring[k] = static_cast<uint32_t>(m.vertex_count());
        for (int c = 0; c < 3; ++c) m.positions.push_back(static_cast<float>(at_ring[k][c]));
        added.push_back(ring[k]);
      }
      zip(m, lower, lower_param, ring, ring_param);
      lower = std::move(ring);
      lower_param = ring_param;
    }
    const auto [upper, upper_param] = reversed_from(lb, sb.param, offset);
    zip(m, lower, lower_param, upper, upper_param);
    // A tube through a part of the surface (a gap that bends away, a part
    // in the way) crosses it all the way round: as many triangles as a ring
    // has or more.  Fewer crossings, where the tube meets a jagged cut end
    // (18 on a double torus cut through at 4,000 points, rings of 25), are
    // the later stages' to untangle.
    if (count_self_intersections(m) > crossings + count) {
      m = before;
      added.resize(added_before);
      continue;
    }
    used[a] = used[b] = 1;
    crossings = count_self_intersections(m);  // the next tube is judged by its own crossings
    ++built;
  }
  if (unbridged_pairs) {
    *unbridged_pairs = 0;
    std::vector<uint8_t> counted = used;
    for (const auto& [a, b] : doubtful)
      if (!counted[a] && !counted[b]) counted[a] = counted[b] = 1, ++*unbridged_pairs;
  }
  std::vector<std::vector<uint32_t>> rest;
  for (size_t l = 0; l < nl; ++l)
    if (!used[l]) rest.push_back(std::move(loops[l]));
  loops = std::move(rest);
  return built;
}

}  // namespace dbss
