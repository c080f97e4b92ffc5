#include "dbss/encoder/creases.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unordered_set>

#include <Eigen/Dense>

#include "dbss/decoder/level_refiner.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/crease_align.h"
#include "dbss/encoder/point_distances.h"
#include "crease_off_points.h"
#include "crease_shape.h"
#include "crease_short_edges.h"
#include "crease_slivers.h"

namespace dbss {

namespace {

using V3 = std::array<double, 3>;

V3 at(const std::vector<float>& p, uint32_t v) { return {p[3 * size_t{v}], p[3 * size_t{v} + 1], p[3 * size_t{v} + 2]}; }
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const V3& a) { return std::sqrt(dot(a, a)); }

// The component of d across the edge direction e (unit).
V3 across(const V3& d, const V3& e) {
  const double t = dot(d, e);
  return {d[0] - t * e[0], d[1] - t * e[1], d[2] - t * e[2]};
}

struct Plane {
  V3 point, normal;
};

V3 cross(const V3& a, const V3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }

// Triangles (u, w, c) and (w, u, d) within 3 degrees of one plane.
bool flat_pair(const V3& u, const V3& w, const V3& c, const V3& d) {
  const V3 a = cross(sub(w, u), sub(c, u)), b = cross(sub(u, w), sub(d, w));
  const double la = norm(a), lb = norm(b);
  return la > 0 && lb > 0 && dot(a, b) > std::cos(3 * 3.14159265358979323846 / 180) * la * lb;
}

// RMS distance of the points from their plane.
double rms(const PointPlane& p) { return std::sqrt(std::max(0.0, p.variance[0])); }

// RMS distance of the points `near` from the quadric height field
// h = c0 + c1 x + c2 y + c3 x^2 + c4 xy + c5 y^2 that fits them best, over
// the plane through `origin` with unit axes x, y and normal z; negative when
// the fit is ill-posed.  Six coefficients, as many as two planes have: the
// smooth surface's best against the crease's best at equal freedom.
double quadric_rms(const PointCloud& pc, const std::vector<uint32_t>& near, const V3& origin, const V3& x, const V3& y, const V3& z) {
  if (near.size() < 12) return -1;
  Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> atb = Eigen::Matrix<double, 6, 1>::Zero();
  double scale2 = 0;
  for (uint32_t i : near) {
    const V3 d = sub(at(pc.xyz, i), origin);
    scale2 = std::max(scale2, dot(d, d));
  }
  const double s = scale2 > 0 ? 1 / std::sqrt(scale2) : 1;  // coordinates in units of the neighbourhood
  const auto row = [&](uint32_t i, Eigen::Matrix<double, 6, 1>& r) {
    const V3 d = sub(at(pc.xyz, i), origin);
    const double u = dot(d, x) * s, v = dot(d, y) * s;
    r << 1, u, v, u * u, u * v, v * v;
    return dot(d, z) * s;
  };
  Eigen::Matrix<double, 6, 1> r;
  for (uint32_t i : near) {
    const double h = row(i, r);
    ata += r * r.transpose(), atb += h * r;
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(ata);
  if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-12)) return -1;
  const Eigen::Matrix<double, 6, 1> c = ldlt.solve(atb);
  double sum = 0;
  for (uint32_t i : near) {
    const double h = row(i, r);
    sum += (h - c.dot(r)) * (h - c.dot(r));
  }
  return std::sqrt(sum / static_cast<double>(near.size())) / s;
}

// CreaseOptions::chain_run_ratio: chain edges too short for their own
// test (too few points, a side too small) are judged together.  The chain
// edges, passed and unfit, joined at their vertices make runs; a run with
// an edge that passed keeps its unfit edges (a rim's short edges between
// long ones), and so does a run of more than kShortRun edges (a line the
// alignment followed that far; the cylinder's rim arcs: one test over a
// curved arc's union fails for the planes, not for the feature).  A lone
// run of one or two edges is tested once over its edges' neighbourhoods
// widened to their kRunNearest nearest points each: two planes split along
// its line against one quadric height field, as for a single edge; it
// keeps its tags only when the quadric fits chain_run_ratio times worse,
// and loses them when even those points do not fit two sides.  Untested,
// such runs were bunny00's last false tags (bench/crease_bench.md).
constexpr size_t kShortRun = 2;      // edges: a longer run is a line the alignment followed, kept
constexpr size_t kRunNearest = 32;   // points near each edge's midpoint, at least

void judge_unfit_runs(const LevelTopology& t, const TriangleMesh& mesh, const PointIndex& points, const CreaseOptions& o,
                      const std::vector<uint8_t>& state, uint8_t passed, uint8_t unfit, std::vector<uint8_t>& crease, CreaseStats& st) {
  const PointCloud& pc = points.points();
  const uint32_t n = t.vertex_count;
  std::vector<uint32_t> root(n);
  for (uint32_t v = 0; v < n; ++v) root[v] = v;
  const auto find = [&](uint32_t v) {
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
  };
  const auto ends = [&](uint32_t e) { return std::array<uint32_t, 2>{t.triangles[t.edge_half[e]], t.triangles[next_half(t.edge_half[e])]}; };
  for (uint32_t e = 0; e < t.edge_count(); ++e)
    if (state[e] == passed || state[e] == unfit) {
      const auto [u, w] = ends(e);
      root[find(u)] = find(w);
    }
  std::vector<uint8_t> has_passed(n, 0);
  std::vector<std::vector<uint32_t>> runs(n);
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    if (state[e] == passed) has_passed[find(ends(e)[0])] = 1;
    if (state[e] == unfit) runs[find(ends(e)[0])].push_back(e);
  }
  const bool trace = std::getenv("DBSS_CREASE_TRACE") != nullptr;
  std::vector<uint32_t> near, all, side[2];
  for (uint32_t r = 0; r < n; ++r) {
    const std::vector<uint32_t>& run = runs[r];
    if (run.empty()) continue;
    if (has_passed[r] || run.size() > kShortRun) {
      st.chain_edges += run.size();
      continue;
    }
    // The run's frame: its line (edges' directions, turned to agree with
    // the first), the mean of its triangles' normals across it, its centre.
    V3 dir = {0, 0, 0}, z = {0, 0, 0}, origin = {0, 0, 0};
    V3 first = {0, 0, 0};
    size_t used = 0;
    all.clear();
    for (uint32_t e : run) {
      const uint32_t h = t.edge_half[e], tw = t.twin[h];
      const auto [u, w] = ends(e);
      const V3 pu = at(mesh.positions, u), pw = at(mesh.positions, w);
      V3 d = sub(pw, pu);
      const double len = norm(d);
      if (!(len > 0)) continue;
      if (norm(first) == 0) first = d;
      if (dot(d, first) < 0) d = {-d[0], -d[1], -d[2]};
      for (int k = 0; k < 3; ++k) dir[k] += d[k], origin[k] += 0.5 * (pu[k] + pw[k]);
      ++used;
      for (uint32_t hh : {h, tw}) {
        const V3 a = at(mesh.positions, t.triangles[hh]);
        const V3 nf = cross(sub(at(mesh.positions, t.triangles[next_half(hh)]), a), sub(at(mesh.positions, t.triangles[prev_half(hh)]), a));
        const double l = norm(nf);
        if (l > 0)
          for (int k = 0; k < 3; ++k) z[k] += nf[k] / l;
      }
      const float mid[3] = {float(0.5 * (pu[0] + pw[0])), float(0.5 * (pu[1] + pw[1])), float(0.5 * (pu[2] + pw[2]))};
      points.within(mid, float(0.6 * len), near);
      all.insert(all.end(), near.begin(), near.end());
      uint32_t knn[kRunNearest];
      float d2[kRunNearest];
      const size_t got = points.nearest_k(mid, kRunNearest, knn, d2);
      all.insert(all.end(), knn, knn + got);
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    const double ld = norm(dir);
    bool judged = false, smooth = false;
    double ratio = 0;
    for (double& k : origin) k /= static_cast<double>(std::max<size_t>(used, 1));
    if (ld > 0 && all.size() >= 2 * o.min_side_points) {
      for (double& k : dir) k /= ld;
      z = across(z, dir);
      const double lz = norm(z);
      if (lz > 1e-6) {
        for (double& k : z) k /= lz;
        const V3 y = cross(z, dir);
        // First split: either side of the run's line, across it in the
        // triangles' plane; then twice to the nearer plane, as for an edge.
        side[0].clear(), side[1].clear();
        for (uint32_t i : all) side[dot(sub(at(pc.xyz, i), origin), y) >= 0 ? 0 : 1].push_back(i);
        PointPlane fit[2];
        bool ok = side[0].size() >= o.min_side_points && side[1].size() >= o.min_side_points;
        for (int round = 0; round < 3 && ok; ++round) {
          fit[0] = fit_plane(pc, side[0].data(), side[0].size());
          fit[1] = fit_plane(pc, side[1].data(), side[1].size());
          if (round == 2) break;
          side[0].clear(), side[1].clear();
          for (uint32_t i : all) {
            const V3 p = at(pc.xyz, i);
            const double d0 = std::abs(dot(sub(p, V3(fit[0].point)), V3(fit[0].normal)));
            const double d1 = std::abs(dot(sub(p, V3(fit[1].point)), V3(fit[1].normal)));
            side[d0 <= d1 ? 0 : 1].push_back(i);
          }
          ok = side[0].size() >= o.min_side_points && side[1].size() >= o.min_side_points;
        }
        const double q = ok ? quadric_rms(pc, all, origin, dir, y, z) : -1;
        if (q >= 0) {
          const double n0 = static_cast<double>(side[0].size()), n1 = static_cast<double>(side[1].size());
          const double two = std::sqrt(std::max(0.0, (n0 * fit[0].variance[0] + n1 * fit[1].variance[0]) / (n0 + n1)));
          ratio = q / std::max(two, 1e-9 * std::max(q, 1e-30));
          judged = true;
          smooth = ratio < o.chain_run_ratio;
        }
      }
    }
    if (trace)
      std::fprintf(stderr, "crease-trace run edges %zu points %zu %s ratio %.3f at %.4f %.4f %.4f\n", run.size(), all.size(),
                   !judged ? "unfit-dropped" : smooth ? "smooth-dropped" : "kept", ratio, origin[0], origin[1], origin[2]);
    if (smooth || !judged) {
      for (uint32_t e : run) crease[e] = 0;
      if (smooth) st.smooth_rejected += run.size();
      st.chain_runs_dropped += run.size();
    } else {
      st.chain_edges += run.size();
    }
  }
}

// Each edge's level-1 stencil point's distance from the edge's midpoint,
// over the edge's length, with the tags `tags` (by the decoder's own
// rules; empty when the mesh cannot be refined).
std::vector<double> stencil_offsets(const TriangleMesh& mesh, const format::Creases& tags) {
  std::vector<double> off;
  auto refiner = LevelRefiner::create(mesh, tags);
  if (!refiner.ok()) return off;
  off.assign(refiner.value().next_odd_count(), 0);
  std::vector<int32_t> q;
  refiner.value().refine(
      [&](uint32_t e, const double p[3], const double*, const float* u, const float* w) {
        double d2 = 0, l2 = 0;
        for (int k = 0; k < 3; ++k) {
          const double m = 0.5 * (double{u[k]} + double{w[k]});
          d2 += (p[k] - m) * (p[k] - m), l2 += (double{w[k]} - u[k]) * (double{w[k]} - u[k]);
        }
        off[e] = l2 > 0 ? std::sqrt(d2 / l2) : 0;
        return 0;
      },
      1.0f, q, 1);
  return off;
}

// CreaseOptions::flat_corners: a smooth vertex (no crease edge, no tag,
// not on the boundary) of valence other than 6 whose triangles all lie
// within `degrees` of its first one's plane is tagged corner when that
// brings the stencil points of its edges nearer their midpoints (the
// largest offset over its edges, at level 1, by the decoder's rules): its
// edges then take the eight-point rule (decoding.md 5.2), not the
// extraordinary one (5.3), whose whole-ring stencil overshoots across a
// lopsided fan beside a feature line.  On a flat fan both stay in its
// plane; what differs is where in it, and an odd vertex pushed past a
// feature line in the face's plane is beyond any displacement's reach.
// Tagging every such vertex raised the fandisk's level 1 by 12% (seed 1):
// beside some lines the eight-point rule is the one that overshoots.
// A stencil point this far from its edge's midpoint (in edge lengths) is an
// overshoot worth a tag; smaller offsets are the butterfly's ordinary work
// (tagging every flat fan where the eight-point rule's offsets were smaller
// raised the fandisk's level 3 by 9% at seed 1: the tag stays at every
// level, where the extraordinary rule's ring is regular again).
constexpr double kOvershoot = 0.25;

// Rounds of collapse_short_edges (CreaseOptions::short_collapses).
constexpr int kCollapseRounds = 4;

void tag_flat_fans(const TriangleMesh& mesh, const LevelTopology& t, const std::vector<uint32_t>& count, double degrees,
                   bool fit_plane, bool check, format::Creases& out, CreaseStats& st) {
  const double flat = std::cos(degrees * 3.14159265358979323846 / 180);
  const uint32_t n = t.vertex_count;
  std::vector<uint32_t> valence(n, 0);
  std::vector<uint8_t> bent(n, 0), boundary(n, 0);
  std::vector<V3> first(n, V3{0, 0, 0});
  for (uint32_t h = 0; h < t.triangles.size(); ++h)
    if (t.twin[h] == kNoHalfEdge) boundary[t.triangles[h]] = 1, boundary[t.triangles[next_half(h)]] = 1;
  for (size_t f = 0; f < mesh.triangle_count(); ++f) {
    const uint32_t* c = &mesh.triangles[3 * f];
    const V3 a = at(mesh.positions, c[0]);
    V3 nf = cross(sub(at(mesh.positions, c[1]), a), sub(at(mesh.positions, c[2]), a));
    const double l = norm(nf);
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = c[k];
      ++valence[v];
      if (!(l > 0)) {
        bent[v] = 1;
        continue;
      }
      const V3 u = {nf[0] / l, nf[1] / l, nf[2] / l};
      if (valence[v] == 1) first[v] = u;
      else if (dot(u, first[v]) <= flat) bent[v] = 1;
    }
  }
  if (fit_plane) {
    // Flat against the fan's area-weighted plane: each ring vertex within
    // sin(degrees) of the fan's mean edge length from it (CreaseOptions::
    // flat_fan_fit).  A zero or turned triangle still bends the fan.
    std::vector<V3> sum(n, V3{0, 0, 0});
    std::vector<double> edge_sum(n, 0);
    for (size_t f = 0; f < mesh.triangle_count(); ++f) {
      const uint32_t* c = &mesh.triangles[3 * f];
      const V3 a = at(mesh.positions, c[0]);
      const V3 nf = cross(sub(at(mesh.positions, c[1]), a), sub(at(mesh.positions, c[2]), a));
      for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 3; ++i) sum[c[k]][i] += nf[i];
        edge_sum[c[k]] += norm(sub(at(mesh.positions, c[(k + 1) % 3]), at(mesh.positions, c[k])));
      }
    }
    const double tol = std::sin(degrees * 3.14159265358979323846 / 180);
    std::fill(bent.begin(), bent.end(), 0);
    for (size_t f = 0; f < mesh.triangle_count(); ++f) {
      const uint32_t* c = &mesh.triangles[3 * f];
      const V3 a = at(mesh.positions, c[0]);
      const V3 nf = cross(sub(at(mesh.positions, c[1]), a), sub(at(mesh.positions, c[2]), a));
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = c[k];
        const double l = norm(sum[v]);
        if (!(l > 0) || !(norm(nf) > 0) || dot(nf, sum[v]) <= 0) {
          bent[v] = 1;
          continue;
        }
        const double reach = tol * edge_sum[v] / valence[v];
        for (int j = 1; j < 3; ++j)
          if (std::abs(dot(sub(at(mesh.positions, c[(k + j) % 3]), at(mesh.positions, v)), sum[v])) > reach * l) bent[v] = 1;
      }
    }
  }
  std::vector<uint32_t> candidates;
  for (uint32_t v = 0; v < n; ++v)
    if (count[v] == 0 && !out.corner[v] && !boundary[v] && !bent[v] && valence[v] != 6 && valence[v] >= 3) candidates.push_back(v);
  if (candidates.empty()) return;
  format::Creases all = out;
  for (uint32_t v : candidates) all.corner[v] = 1;
  const std::vector<double> before = stencil_offsets(mesh, out), after = stencil_offsets(mesh, all);
  if (before.size() != t.edge_count() || after.size() != t.edge_count()) return;
  std::vector<double> worst_before(n, 0), worst_after(n, 0);
  const auto worst_at = [&](const std::vector<double>& off, std::vector<double>& worst) {
    std::fill(worst.begin(), worst.end(), 0);
    for (uint32_t e = 0; e < t.edge_count(); ++e)
      for (uint32_t v : {t.triangles[t.edge_half[e]], t.triangles[next_half(t.edge_half[e])]}) worst[v] = std::max(worst[v], off[e]);
  };
  worst_at(before, worst_before), worst_at(after, worst_after);
  format::Creases chosen = out;
  for (uint32_t v : candidates)
    if (worst_before[v] > kOvershoot && worst_after[v] < 0.5 * worst_before[v]) chosen.corner[v] = 1;
  // The check (CreaseOptions::flat_fan_check): the chosen tags judged as
  // they end up, with the rejected candidates untagged.
  for (int round = 0; round < (check ? 3 : 0); ++round) {
    const std::vector<double> final_off = stencil_offsets(mesh, chosen);
    if (final_off.size() != t.edge_count()) break;
    worst_at(final_off, worst_after);
    bool changed = false;
    for (uint32_t v : candidates)
      if (chosen.corner[v] && !(worst_after[v] < 0.5 * worst_before[v])) chosen.corner[v] = 0, changed = true, ++st.flat_corners_dropped;
    if (!changed) break;
  }
  for (uint32_t v : candidates)
    if (chosen.corner[v]) out.corner[v] = 1, ++st.flat_corners;
}

}  // namespace

format::Creases find_creases(TriangleMesh& mesh, const PointIndex& points, const CreaseOptions& o, CreaseStats* stats) {
  CreaseStats st;
  format::Creases out;
  if (!(o.angle_degrees > 0)) {
    if (stats) *stats = st;
    return out;
  }
  // Edges along the features first: the test below only finds crease
  // edges the control mesh has.
  // A mesh in which no tag is found is given back as it came: the file is
  // then the one creases off writes, byte for byte.
  const std::vector<float> unaligned = mesh.positions;
  const std::vector<uint32_t> unaligned_triangles = mesh.triangles;
  AlignStats aligned;
  std::vector<std::array<uint32_t, 2>> chains;
  std::vector<uint32_t> corners;
  align_to_features(mesh, points, o, &aligned, &chains, &corners);
  st.aligned = aligned.snapped, st.align_flips = aligned.flips, st.align_splits = aligned.splits;
  st.align_collapses = aligned.collapses;
  st.align_relaxed = aligned.relaxed;
  st.align_valence_flips = aligned.valence_flips;
  auto built = build_topology(static_cast<uint32_t>(mesh.vertex_count()), mesh.triangles);
  if (!built.ok()) {  // no tags either way: the mesh as it came (review)
    mesh.positions = unaligned, mesh.triangles = unaligned_triangles;
    if (stats) *stats = st;
    return out;
  }
  const LevelTopology& t = built.value();
  const PointCloud& pc = points.points();
  const double min_cos = std::cos(o.angle_degrees * 3.14159265358979323846 / 180);
  std::vector<uint8_t> crease(t.edge_count(), 0);
  std::vector<std::vector<Plane>> planes(t.vertex_count);  // the sides' planes at each crease vertex
  std::vector<uint32_t> near, side[2];
  // Read once: the edge loop below judges thousands of edges.
  const bool trace = std::getenv("DBSS_CREASE_TRACE") != nullptr;
  // Chain edges by how their own test went: passed, or too short for it
  // (tagged for now; judged as a run below).
  enum : uint8_t { kNotChain, kPassed, kUnfit };
  std::vector<uint8_t> chain_state(t.edge_count(), kNotChain);
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t h = t.edge_half[e], tw = t.twin[h];
    if (tw == kNoHalfEdge) continue;
    // An edge of a chain along a feature line: its ends are on the line
    // already; it keeps its tag unless the smooth test below finds a single
    // smooth sheet through its points.
    const uint32_t ca = std::min(t.triangles[h], t.triangles[next_half(h)]), cb = std::max(t.triangles[h], t.triangles[next_half(h)]);
    const bool chain = std::binary_search(chains.begin(), chains.end(), std::array<uint32_t, 2>{ca, cb});
    const auto keep_chain = [&] {
      if (!chain) return;
      crease[e] = 1, chain_state[e] = kUnfit;
    };
    const uint32_t u = t.triangles[h], w = t.triangles[next_half(h)];
    const V3 pu = at(mesh.positions, u), pw = at(mesh.positions, w);
    const V3 pc1 = at(mesh.positions, t.triangles[prev_half(h)]), pd = at(mesh.positions, t.triangles[prev_half(tw)]);
    const double len = norm(sub(pw, pu));
    if (!(len > 0)) { keep_chain(); continue; }
    // Its two triangles in one plane: the control mesh has no fold here,
    // so the feature is beside this edge, not along it (the points within
    // 0.6 of a short edge next to a line see both sides).  Tagged, it
    // would be a spur with a dart at its end (CreaseOptions::untag_flat).
    if (!chain && o.untag_flat && flat_pair(pu, pw, pc1, pd)) continue;
    const V3 dir = {(pw[0] - pu[0]) / len, (pw[1] - pu[1]) / len, (pw[2] - pu[2]) / len};
    const double radius = 0.6 * len;
    const float mid[3] = {float(0.5 * (pu[0] + pw[0])), float(0.5 * (pu[1] + pw[1])), float(0.5 * (pu[2] + pw[2]))};
    points.within(mid, float(radius), near);
    if (near.size() < 2 * o.min_side_points) { keep_chain(); continue; }
    // First split: toward the third corner of either triangle.
    V3 t1 = across(sub(pc1, pu), dir), t2 = across(sub(pd, pu), dir);
    const double l1 = norm(t1), l2 = norm(t2);
    if (!(l1 > 0) || !(l2 > 0)) { keep_chain(); continue; }
    for (int k = 0; k < 3; ++k) t1[k] /= l1, t2[k] /= l2;
    side[0].clear(), side[1].clear();
    for (uint32_t i : near) {
      const V3 q = across(sub(at(pc.xyz, i), pu), dir);
      side[dot(q, t1) >= dot(q, t2) ? 0 : 1].push_back(i);
    }
    if (side[0].size() < o.min_side_points || side[1].size() < o.min_side_points) { keep_chain(); continue; }
    // Then twice: each point to the plane it is nearer, planes refitted.
    PointPlane fit[2];
    bool ok = true;
    for (int round = 0; round < 3 && ok; ++round) {
      fit[0] = fit_plane(pc, side[0].data(), side[0].size());
      fit[1] = fit_plane(pc, side[1].data(), side[1].size());
      if (round == 2) break;
      side[0].clear(), side[1].clear();
      for (uint32_t i : near) {
        const V3 p = at(pc.xyz, i);
        const double d0 = std::abs(dot(sub(p, V3(fit[0].point)), V3(fit[0].normal)));
        const double d1 = std::abs(dot(sub(p, V3(fit[1].point)), V3(fit[1].normal)));
        side[d0 <= d1 ? 0 : 1].push_back(i);
      }
      ok = side[0].size() >= o.min_side_points && side[1].size() >= o.min_side_points;
    }
    if (!ok) { keep_chain(); continue; }
    if (!chain) ++st.edges_tested;
    // A smooth surface, not a crease: one quadric height field (over the
    // plane of the edge's two control triangles) fits the points about as
    // well as the two planes do (CreaseOptions::smooth_ratio).  On a curved
    // sheet the planes' misfit is its curvature, which the quadric has; on
    // noise both fit alike; across a crease the quadric cannot bend sharply.
    bool smooth = false;
    double ratio = 0, trace_q = 0, trace_p = 0;
    const auto judge = [&] {  // only for an edge the other tests would tag (the fit costs)
      const V3 na = cross(sub(pw, pu), sub(pc1, pu)), nb = cross(sub(pu, pw), sub(pd, pw));
      const double la = norm(na), lb = norm(nb);
      V3 z = {0, 0, 0};
      if (la > 0 && lb > 0) z = {na[0] / la + nb[0] / lb, na[1] / la + nb[1] / lb, na[2] / la + nb[2] / lb};
      z = across(z, dir);
      const double lz = norm(z);
      if (lz > 1e-6) {
        for (double& k : z) k /= lz;
        const V3 y = cross(z, dir);
        const V3 origin = {0.5 * (pu[0] + pw[0]), 0.5 * (pu[1] + pw[1]), 0.5 * (pu[2] + pw[2])};
        const double q = quadric_rms(pc, near, origin, dir, y, z);
        const double n0 = static_cast<double>(side[0].size()), n1 = static_cast<double>(side[1].size());
        const double two = std::sqrt(std::max(0.0, (n0 * fit[0].variance[0] + n1 * fit[1].variance[0]) / (n0 + n1)));
        if (q >= 0) {
          ratio = q / std::max(two, 1e-9 * radius);
          smooth = o.smooth_ratio > 0 && ratio < o.smooth_ratio;
        }
        trace_q = q / radius, trace_p = two / radius;
      }
      if (trace)
        std::fprintf(stderr, "crease-trace %s angle %.1f ratio %.3f quad %.4f planes %.4f (of radius) at %.4f %.4f %.4f\n", chain ? "chain" : "edge",
                     std::acos(std::min(1.0, std::abs(dot(V3(fit[0].normal), V3(fit[1].normal))))) * 180 / 3.14159265358979323846, ratio,
                     trace_q, trace_p, 0.5 * (pu[0] + pw[0]), 0.5 * (pu[1] + pw[1]), 0.5 * (pu[2] + pw[2]));
    };
    if (chain) {
      judge();
      if (smooth) ++st.smooth_rejected;
      else crease[e] = 1, chain_state[e] = kPassed, ++st.chain_edges;
      continue;
    }
    const double c = std::abs(dot(V3(fit[0].normal), V3(fit[1].normal)));
    if (c > min_cos) continue;  // the planes meet at less than the angle
    if (rms(fit[0]) > o.flatness * radius || rms(fit[1]) > o.flatness * radius) continue;  // a bend, not a crease
    // The feature must run along this edge, not beside it (an edge of a
    // flat face next to a crease sees two planes too): the planes' line
    // parallel to the edge and both ends near both planes.
    const V3 n0 = V3(fit[0].normal), n1 = V3(fit[1].normal);
    V3 line = {n0[1] * n1[2] - n0[2] * n1[1], n0[2] * n1[0] - n0[0] * n1[2], n0[0] * n1[1] - n0[1] * n1[0]};
    const double ll = norm(line);
    if (!(ll > 0) || std::abs(dot(line, dir)) < o.parallel * ll) continue;
    bool along = true;
    for (const V3& end : {pu, pw})
      for (int s = 0; s < 2; ++s)
        along = along && std::abs(dot(sub(end, V3(fit[s].point)), V3(fit[s].normal))) <= o.reach * len;
    if (!along) continue;
    judge();
    if (smooth) {
      ++st.smooth_rejected;
      continue;
    }
    crease[e] = 1;
    for (int s = 0; s < 2; ++s) {
      const Plane p{V3(fit[s].point), V3(fit[s].normal)};
      planes[u].push_back(p), planes[w].push_back(p);
    }
  }
  if (o.chain_run_ratio > 0) judge_unfit_runs(t, mesh, points, o, chain_state, kPassed, kUnfit, crease, st);
  else
    for (uint32_t e = 0; e < t.edge_count(); ++e) st.chain_edges += chain_state[e] == kUnfit;
  std::vector<uint32_t> count(t.vertex_count, 0);
  const auto count_creases = [&] {
    std::fill(count.begin(), count.end(), 0);
    for (uint32_t e = 0; e < t.edge_count(); ++e)
      if (crease[e]) ++count[t.triangles[t.edge_half[e]]], ++count[t.triangles[next_half(t.edge_half[e])]];
  };
  count_creases();
  // Close gaps: an edge between two crease ends (one crease edge each) that
  // continues both their creases (within 35 degrees) is a crease the test
  // missed (too few points on one side, a side not flat at a corner); left
  // open, the polyline would stop there and the edge be rounded.
  {
    std::vector<V3> end_dir(t.vertex_count, V3{0, 0, 0});  // from the other end of its one crease edge towards it
    for (uint32_t e = 0; e < t.edge_count(); ++e) {
      if (!crease[e]) continue;
      const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[next_half(h)];
      const V3 d = sub(at(mesh.positions, w), at(mesh.positions, u));
      const double l = norm(d);
      if (count[w] == 1) end_dir[w] = {d[0] / l, d[1] / l, d[2] / l};
      if (count[u] == 1) end_dir[u] = {-d[0] / l, -d[1] / l, -d[2] / l};
    }
    for (uint32_t e = 0; e < t.edge_count(); ++e) {
      const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[next_half(h)];
      if (crease[e] || t.twin[h] == kNoHalfEdge || count[u] != 1 || count[w] != 1) continue;
      const V3 d = sub(at(mesh.positions, w), at(mesh.positions, u));
      const double l = norm(d);
      const V3 uw = {d[0] / l, d[1] / l, d[2] / l};
      if (dot(end_dir[u], uw) > 0.82 && -dot(end_dir[w], uw) > 0.82) {
        crease[e] = 1;
        ++st.gaps_closed;
        // The neighbouring crease edges' planes serve this edge's vertices.
      }
    }
    count_creases();
  }
  // Bridge the rest: a crease end (a dart) whose direction goes on, within
  // kBridge, along one edge or two to another end that comes the other way
  // or to a vertex aligned onto a corner.  Left open, each such gap is two
  // darts, and the butterfly rounds the feature there over a whole control
  // edge's reach on every level (the cube: 94 darts for its 8 corners).
  {
    constexpr double kBridge = 0.9;  // cos 25 degrees, per edge of the bridge
    std::vector<uint8_t> is_corner(t.vertex_count, 0);
    for (uint32_t v : corners)
      if (v < t.vertex_count) is_corner[v] = 1;
    std::vector<std::vector<uint32_t>> edges_at(t.vertex_count);
    for (uint32_t e = 0; e < t.edge_count(); ++e) {
      const uint32_t h = t.edge_half[e];
      if (t.twin[h] == kNoHalfEdge) continue;
      edges_at[t.triangles[h]].push_back(e), edges_at[t.triangles[next_half(h)]].push_back(e);
    }
    const auto other = [&](uint32_t e, uint32_t v) {
      const uint32_t h = t.edge_half[e], a = t.triangles[h];
      return a == v ? t.triangles[next_half(h)] : a;
    };
    const auto toward = [&](uint32_t a, uint32_t b) {
      const V3 d = sub(at(mesh.positions, b), at(mesh.positions, a));
      const double l = norm(d);
      return l > 0 ? V3{d[0] / l, d[1] / l, d[2] / l} : V3{0, 0, 0};
    };
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<V3> end_dir(t.vertex_count, V3{0, 0, 0});  // a dart's crease direction, pointing out of it
      for (uint32_t e = 0; e < t.edge_count(); ++e) {
        if (!crease[e]) continue;
        const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[next_half(h)];
        if (count[u] == 1) end_dir[u] = toward(w, u);
        if (count[w] == 1) end_dir[w] = toward(u, w);
      }
      // Where a bridge may end: a dart coming the other way, or a corner.
      const auto lands = [&](uint32_t y, const V3& dir) {
        if (is_corner[y]) return true;
        return count[y] == 1 && !is_corner[y] && -dot(end_dir[y], dir) > kBridge;
      };
      size_t bridged = 0;
      for (uint32_t u = 0; u < t.vertex_count; ++u) {
        if (count[u] != 1 || is_corner[u]) continue;
        const V3 dir = end_dir[u];
        bool done = false;
        for (uint32_t e1 : edges_at[u]) {
          if (done || crease[e1]) continue;
          const uint32_t x = other(e1, u);
          if (dot(toward(u, x), dir) <= kBridge) continue;
          if (lands(x, dir)) {
            crease[e1] = 1, ++count[u], ++count[x], done = true, ++bridged;
            continue;
          }
          if (count[x] != 0) continue;
          for (uint32_t e2 : edges_at[x]) {
            const uint32_t y = other(e2, x);
            if (y == u || crease[e2] || dot(toward(x, y), dir) <= kBridge || !lands(y, dir)) continue;
            crease[e1] = crease[e2] = 1, count[u] += 1, count[x] += 2, count[y] += 1, done = true, bridged += 2;
            break;
          }
        }
      }
      st.gaps_closed += bridged;
      if (bridged == 0) break;
    }
  }
  // Spurs: an edge the test tagged beside a chain (one end a dart, the
  // other on a chain with two more crease edges) is an edge of a face
  // next to the feature, not the feature; left, it makes a false corner
  // and a dart.
  for (bool again = true; again;) {
    again = false;
    for (uint32_t e = 0; e < t.edge_count(); ++e) {
      if (!crease[e]) continue;
      const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[next_half(h)];
      if (std::binary_search(chains.begin(), chains.end(), std::array<uint32_t, 2>{std::min(u, w), std::max(u, w)})) continue;
      if ((count[u] == 1 && count[w] >= 3) || (count[w] == 1 && count[u] >= 3)) {
        crease[e] = 0, --count[u], --count[w], again = true;
        ++st.spurs;
      }
    }
  }
  for (uint32_t e = 0; e < t.edge_count(); ++e) st.creases += crease[e];
  // A vertex moved onto three planes' common point is a corner where any
  // crease reaches it (a chain that ends there is not a dart).
  std::vector<uint8_t> at_corner(t.vertex_count, 0);
  for (uint32_t v : corners)
    if (v < t.vertex_count && count[v] >= 1) at_corner[v] = 1;
  for (uint32_t v = 0; v < t.vertex_count; ++v) st.darts += count[v] == 1 && !at_corner[v];
  // Too few to pay for a tagged file (CreaseOptions::min_share): stray
  // tags on a smooth shape, or a feature too small to matter.
  if (st.creases > 0 && o.min_share > 0 && static_cast<double>(st.creases) < o.min_share * static_cast<double>(t.edge_count())) {
    st.too_few_dropped = st.creases;
    st.creases = 0, st.corners = 0, st.darts = 0;
  }
  // In pieces (CreaseOptions::max_dart_share): a feature the control mesh
  // does not resolve, tagged where a stretch of it passed the test.
  if (st.creases > 0 && o.max_dart_share > 0 && static_cast<double>(st.darts) > o.max_dart_share * static_cast<double>(st.creases)) {
    st.in_pieces_dropped = st.creases;
    st.creases = 0, st.corners = 0, st.darts = 0;
  }
  if (st.creases == 0) {
    mesh.positions = unaligned, mesh.triangles = unaligned_triangles;
    if (stats) *stats = st;
    return out;
  }
  out.edge = crease;
  out.corner.assign(t.vertex_count, 0);
  // Shortest edge at each vertex: bounds its move.
  std::vector<double> shortest(t.vertex_count, INFINITY);
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[next_half(h)];
    const double l = norm(sub(at(mesh.positions, u), at(mesh.positions, w)));
    shortest[u] = std::min(shortest[u], l), shortest[w] = std::min(shortest[w], l);
  }
  std::vector<float> moved = mesh.positions;
  for (uint32_t v = 0; v < t.vertex_count; ++v) {
    if (count[v] >= 3 || at_corner[v]) out.corner[v] = 1, ++st.corners;
    if (planes[v].empty()) continue;
    // Least squares over the planes, with a weak pull to where the vertex
    // is (it fixes the position along a feature line, and regularizes
    // nearly parallel planes): (sum n n^T + lambda I) x = sum n (n.c) + lambda v.
    const V3 pv = at(mesh.positions, v);
    const double lambda = 1e-2;
    double a[3][4] = {};
    for (int i = 0; i < 3; ++i) a[i][i] = lambda, a[i][3] = lambda * pv[i];
    for (const Plane& p : planes[v]) {
      const double d = dot(p.normal, p.point);
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) a[i][j] += p.normal[i] * p.normal[j];
        a[i][3] += p.normal[i] * d;
      }
    }
    // Gaussian elimination with partial pivoting (the matrix is positive definite).
    for (int c = 0; c < 3; ++c) {
      int piv = c;
      for (int r = c + 1; r < 3; ++r)
        if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
      for (int k = 0; k < 4; ++k) std::swap(a[c][k], a[piv][k]);
      for (int r = 0; r < 3; ++r) {
        if (r == c) continue;
        const double f = a[r][c] / a[c][c];
        for (int k = c; k < 4; ++k) a[r][k] -= f * a[c][k];
      }
    }
    const V3 x = {a[0][3] / a[0][0], a[1][3] / a[1][1], a[2][3] / a[2][2]};
    const double move = norm(sub(x, pv));
    if (!std::isfinite(move) || move > shortest[v] / 2) continue;
    for (int k = 0; k < 3; ++k) moved[3 * size_t{v} + k] = static_cast<float>(x[k]);
    ++st.snapped;
    st.max_snap = std::max(st.max_snap, move);
  }
  mesh.positions = std::move(moved);
  // Slivers along the lines, after the snap has put their apex on it
  // (crease_slivers.h); the flat fans are judged on the mesh as it ends up.
  LevelTopology flipped, collapsed;
  if (o.sliver_flips) st.sliver_flips = flip_slivers(mesh, t, out, count, flipped);
  const LevelTopology& flipped_t = st.sliver_flips > 0 ? flipped : t;
  // A few rounds: each round collapses at most one edge per neighbourhood.
  for (int round = 0; round < kCollapseRounds && o.short_collapses; ++round) {
    LevelTopology next;
    const size_t made = collapse_short_edges(mesh, st.short_collapses > 0 ? collapsed : flipped_t, out, count, next);
    if (made == 0) break;
    st.short_collapses += made, collapsed = std::move(next);
  }
  const LevelTopology& cleaned_t = st.short_collapses > 0 ? collapsed : flipped_t;
  LevelTopology shaped;
  if (o.shape_after_tags) {
    const ShapeStats shape = shape_tagged_mesh(mesh, cleaned_t, out, count, points, shaped);
    st.shape_flips = shape.flips, st.shape_moves = shape.moves, st.shape_rounds_undone = shape.rounds_undone;
  }
  const LevelTopology& final_t = st.shape_flips > 0 ? shaped : cleaned_t;
  // A flip splits one tagged edge into two: count the tags the file holds.
  if (st.sliver_flips > 0 || st.short_collapses > 0) st.creases = static_cast<size_t>(std::count_if(out.edge.begin(), out.edge.end(), [](uint8_t b) { return b != 0; }));
  // Untagged vertices the builder left off the points, onto them
  // (crease_off_points.h); before the flat fans are judged.
  if (o.settle_off_points) st.settled = settle_off_points(mesh, final_t, out, count, points);
  if (o.flat_corners) tag_flat_fans(mesh, final_t, count, o.flat_fan_degrees, o.flat_fan_fit, o.flat_fan_check, out, st);
  if (stats) *stats = st;
  return out;
}

format::Creases transfer_creases(const TriangleMesh& from, const format::Creases& tags, const TriangleMesh& to) {
  format::Creases out;
  if (tags.empty()) return out;
  // Nearest vertex of `from` for each of `to`'s, by a sweep over x.
  const uint32_t n = static_cast<uint32_t>(from.vertex_count());
  std::vector<uint32_t> order(n);
  for (uint32_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return from.positions[3 * size_t{a}] < from.positions[3 * size_t{b}]; });
  std::vector<uint32_t> match(to.vertex_count());
  for (uint32_t v = 0; v < to.vertex_count(); ++v) {
    const V3 p = at(to.positions, v);
    const auto x_of = [&](uint32_t i) { return double(from.positions[3 * size_t{i}]); };
    size_t start = std::lower_bound(order.begin(), order.end(), p[0], [&](uint32_t i, double x) { return x_of(i) < x; }) - order.begin();
    double best = INFINITY;
    uint32_t best_i = 0;
    for (size_t k = start; k < n && x_of(order[k]) - p[0] < std::sqrt(best); ++k) {
      const double d = dot(sub(at(from.positions, order[k]), p), sub(at(from.positions, order[k]), p));
      if (d < best) best = d, best_i = order[k];
    }
    for (size_t k = start; k-- > 0 && p[0] - x_of(order[k]) < std::sqrt(best);) {
      const double d = dot(sub(at(from.positions, order[k]), p), sub(at(from.positions, order[k]), p));
      if (d < best) best = d, best_i = order[k];
    }
    match[v] = best_i;
  }
  auto ft = build_topology(n, from.triangles);
  auto tt = build_topology(static_cast<uint32_t>(to.vertex_count()), to.triangles);
  if (!ft.ok() || !tt.ok()) return out;
  std::unordered_set<uint64_t> keys;
  const auto key = [](uint64_t a, uint64_t b) { return std::min(a, b) << 32 | std::max(a, b); };
  for (uint32_t e = 0; e < ft.value().edge_count(); ++e)
    if (tags.edge[e]) {
      const uint32_t h = ft.value().edge_half[e];
      keys.insert(key(ft.value().triangles[h], ft.value().triangles[next_half(h)]));
    }
  const LevelTopology& t = tt.value();
  out.edge.assign(t.edge_count(), 0);
  out.corner.assign(t.vertex_count, 0);
  bool any = false;
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t h = t.edge_half[e];
    if (t.twin[h] != kNoHalfEdge && keys.count(key(match[t.triangles[h]], match[t.triangles[next_half(h)]])))
      out.edge[e] = 1, any = true;
  }
  for (uint32_t v = 0; v < t.vertex_count; ++v)
    if (tags.corner[match[v]]) out.corner[v] = 1, any = true;
  if (!any) return {};
  return out;
}

}  // namespace dbss
