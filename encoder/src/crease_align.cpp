#include "dbss/encoder/crease_align.h"
#include "split_ranges.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <unordered_map>
#include <vector>

#include "dbss/encoder/point_distances.h"
#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

namespace {

constexpr double kPi = 3.14159265358979323846;
// Points whose normals are estimated from this many neighbours: enough to
// average sampling noise, few enough that only a narrow band along a
// feature sees both sides.
constexpr size_t kNormalPoints = 12;
// How far a vertex moves onto a line or a corner, in its mean edge
// lengths: QEM crowds vertices near features, up to half an edge beside
// them; the nearest go first, and a move that makes a triangle poorer than
// kMinQuality or turns it over is not made.
constexpr double kLineReach = 0.5, kCornerReach = 0.8, kMinQuality = 0.15;
// A vertex in a gap of its line's chain (CreaseOptions::gap_snaps) moves
// onto it with triangles down to this quality, when the line goes on
// within this many of its edges.
constexpr double kGapQuality = 0.1, kGapSpan = 3;
// A collapse onto a line keeps each remaining triangle within about 45
// degrees of its normal (a triangle of one face stays on it) and the merged
// vertex's valence at most this: the butterfly overshoots round high ones.
constexpr double kKeepNormal = 0.7;
constexpr size_t kMaxValence = 10;
// Relaxation on flat faces: triangles within about 1 degree of one plane.
const double kFlatFan = std::cos(1 * kPi / 180);
constexpr int kRelaxRounds = 8;
// Relaxation beside a line (CreaseOptions::relax_beside_lines): a tenth of
// a degree.
const double kFlatBeside = std::cos(0.1 * kPi / 180);
// The fewest points a vertex's neighbourhood holds.
constexpr size_t kNeighbourhood = 64;
// Two planes are one plane of the part when their normals are this close.
const double kSamePlane = std::cos(15 * kPi / 180);
// A triangle at a vertex of a line is on a flat face's side within this
// angle (valence flips, 3b).
const double kSameSide = std::cos(5 * kPi / 180);
// A chain edge runs along its line within this angle.
const double kAlong = std::sin(20 * kPi / 180);

V3 unit(V3 v) {
  const double l = std::sqrt(dot(v, v));
  return l > 0 ? V3{v[0] / l, v[1] / l, v[2] / l} : V3{0, 0, 0};
}

uint64_t key(uint32_t u, uint32_t v) { return (uint64_t{u} << 32) | v; }

// The vertices of `v`'s triangles `fan` other than v, sorted, each once: as
// many as the triangles when v is interior (fewer on a boundary).
void sorted_ring(const TriangleMesh& m, const std::vector<uint32_t>& fan, uint32_t v, std::vector<uint32_t>& out) {
  out.clear();
  for (uint32_t f : fan)
    for (int k = 0; k < 3; ++k)
      if (m.triangles[3 * f + k] != v) out.push_back(m.triangles[3 * f + k]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

V3 point_of(const PointCloud& pc, uint32_t i) { return {pc.xyz[3 * size_t{i}], pc.xyz[3 * size_t{i} + 1], pc.xyz[3 * size_t{i} + 2]}; }

// A point's normal from its kNormalPoints nearest: the plane through the
// point and two of them that most of the others lie on (within a tenth of
// the neighbourhood's radius), refitted to those.  Beside a crease the plain
// least-squares plane of all of them blends the two sides; this one takes
// the side most of the neighbours are on, up to the feature line.
std::array<double, 3> robust_normal(const PointIndex& points, uint32_t i) {
  const PointCloud& pc = points.points();
  uint32_t near[kNormalPoints], inliers[kNormalPoints];
  float dist2[kNormalPoints];
  const size_t found = points.nearest_k(&pc.xyz[3 * size_t{i}], kNormalPoints, near, dist2);
  if (found < 3) return fit_plane(pc, near, found).normal;
  const V3 p = point_of(pc, i);
  const double tol = 0.1 * std::sqrt(double{dist2[found - 1]});
  size_t best = 0;
  V3 best_n{};
  for (size_t a = 0; a < found; ++a)
    for (size_t b = a + 1; b < found; ++b) {
      const V3 da = sub(point_of(pc, near[a]), p), db = sub(point_of(pc, near[b]), p);
      const V3 c = cross(da, db);
      const double l = std::sqrt(dot(c, c));
      if (!(l > 0.3 * std::sqrt(dot(da, da) * dot(db, db)))) continue;  // nearly in line: no plane
      const V3 nn = {c[0] / l, c[1] / l, c[2] / l};
      size_t count = 0;
      for (size_t j = 0; j < found; ++j) count += std::abs(dot(sub(point_of(pc, near[j]), p), nn)) <= tol;
      if (count > best) best = count, best_n = nn;
    }
  if (best < 3) return fit_plane(pc, near, found).normal;
  size_t m = 0;
  for (size_t j = 0; j < found; ++j)
    if (std::abs(dot(sub(point_of(pc, near[j]), p), best_n)) <= tol) inliers[m++] = near[j];
  return fit_plane(pc, inliers, m).normal;
}

// Unit normals of the points, estimated when first asked for.
class PointNormals {
 public:
  explicit PointNormals(const PointIndex& points) : points_(points), normal_(3 * points.points().size()), known_(points.points().size(), 0) {}
  V3 operator()(uint32_t i) {
    if (!known_[i]) {
      const V3 nn = robust_normal(points_, i);
      for (int a = 0; a < 3; ++a) normal_[3 * size_t{i} + a] = nn[a];
      known_[i] = 1;
    }
    return {normal_[3 * size_t{i}], normal_[3 * size_t{i} + 1], normal_[3 * size_t{i} + 2]};
  }

 private:
  const PointIndex& points_;
  std::vector<double> normal_;
  std::vector<uint8_t> known_;
};

// What the points around a vertex show: nothing, two planes (a line) or
// three (a corner).
struct Feature {
  int planes = 0;
  V3 normal[3]{}, point[3]{};
  V3 target{};  // nearest point of the line, or the corner
  V3 dir{};     // the line's direction (two planes)
};

// Splits `near` into k groups seeded by the normals `seed`, refits each
// group's plane and reassigns points to their nearest plane twice; true
// when every group is a flat patch (not a strip along the feature) and the
// planes meet pairwise at more than the angle.
bool fit_groups(const PointCloud& pc, const std::vector<uint32_t>& near, PointNormals& normals, const V3* seed, int k,
                double radius, double min_cos, const CreaseOptions& o, Feature& f) {
  std::vector<uint32_t> group[3];
  for (uint32_t i : near) {
    const V3 n = normals(i);
    int best = 0;
    for (int j = 1; j < k; ++j)
      if (std::abs(dot(n, seed[j])) > std::abs(dot(n, seed[best]))) best = j;
    group[best].push_back(i);
  }
  PointPlane fit[3];
  for (int round = 0; round < 3; ++round) {
    for (int j = 0; j < k; ++j) {
      if (group[j].size() < o.min_side_points) return false;
      fit[j] = fit_plane(pc, group[j].data(), group[j].size());
    }
    if (round == 2) break;
    for (int j = 0; j < k; ++j) group[j].clear();
    for (uint32_t i : near) {
      const V3 p = point_of(pc, i);
      int best = 0;
      double best_d = INFINITY;
      for (int j = 0; j < k; ++j) {
        const double d = std::abs(dot(sub(p, fit[j].point), fit[j].normal));
        if (d < best_d) best_d = d, best = j;
      }
      group[best].push_back(i);
    }
  }
  for (int j = 0; j < k; ++j) {
    if (std::sqrt(std::max(0.0, fit[j].variance[0])) > o.flatness * radius) return false;
    // A patch, not the strip of points along the feature line.
    if (fit[j].variance[1] < std::pow(0.15 * radius, 2)) return false;
    for (int i = 0; i < j; ++i)
      if (std::abs(dot(fit[i].normal, fit[j].normal)) > min_cos) return false;
  }
  f.planes = k;
  for (int j = 0; j < k; ++j) f.normal[j] = fit[j].normal, f.point[j] = fit[j].point;
  return true;
}

// The point on the planes nearest `v`: with two planes, their line's point
// nearest v; with three, their common point.  False when ill-conditioned.
bool solve_target(Feature& f, const V3& v) {
  Eigen::Matrix3d a;
  Eigen::Vector3d b;
  for (int j = 0; j < f.planes; ++j) {
    for (int c = 0; c < 3; ++c) a(j, c) = f.normal[j][c];
    b[j] = dot(f.normal[j], f.point[j]);
  }
  if (f.planes == 2) {
    f.dir = unit(cross(f.normal[0], f.normal[1]));
    for (int c = 0; c < 3; ++c) a(2, c) = f.dir[c];
    b[2] = dot(f.dir, v);
  }
  Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
  if (lu.rank() < 3) return false;
  const Eigen::Vector3d x = lu.solve(b);
  if (!x.allFinite()) return false;
  f.target = {x[0], x[1], x[2]};
  return true;
}

Feature classify(const PointIndex& points, PointNormals& normals, const V3& v, double radius, double min_cos,
                 const CreaseOptions& o, std::vector<uint32_t>& near) {
  Feature f;
  const float q[3] = {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
  // At least kNeighbourhood points: QEM leaves short edges along features,
  // where 0.6 of an edge holds too few points to fit two planes.
  {
    uint32_t idx[kNeighbourhood];
    float dist2[kNeighbourhood];
    const size_t found = points.nearest_k(q, kNeighbourhood, idx, dist2);
    if (found == kNeighbourhood) radius = std::max(radius, double{std::sqrt(dist2[found - 1])});
  }
  points.within(q, static_cast<float>(radius), near);
  if (near.size() < 2 * o.min_side_points) return f;
  std::sort(near.begin(), near.end());  // the index's order is not the seeds' business
  const PointCloud& pc = points.points();
  // Seeds: normals as far apart as the neighbourhood has (a normal of a
  // point on the feature is a blend of both sides; the extremes are not).
  const auto least_aligned = [&](auto score) {
    uint32_t best = near[0];
    double best_s = INFINITY;
    for (uint32_t i : near) {
      const double s = score(normals(i));
      if (s < best_s) best_s = s, best = i;
    }
    return normals(best);
  };
  V3 seed[3];
  seed[0] = normals(near[0]);
  seed[1] = least_aligned([&](V3 n) { return std::abs(dot(n, seed[0])); });
  seed[0] = least_aligned([&](V3 n) { return std::abs(dot(n, seed[1])); });
  if (std::abs(dot(seed[0], seed[1])) > min_cos) return f;  // one smooth sheet
  seed[2] = least_aligned([&](V3 n) { return std::max(std::abs(dot(n, seed[0])), std::abs(dot(n, seed[1]))); });
  if (std::max(std::abs(dot(seed[2], seed[0])), std::abs(dot(seed[2], seed[1]))) <= min_cos &&
      fit_groups(pc, near, normals, seed, 3, radius, min_cos, o, f) && solve_target(f, v))
    return f;
  f = Feature{};
  if (fit_groups(pc, near, normals, seed, 2, radius, min_cos, o, f) && solve_target(f, v)) return f;
  return Feature{};
}

// Planes `a` and `b` have in common (same normal, each other's points on it).
int shared_planes(const Feature& a, const Feature& b, double tolerance, int* which = nullptr) {
  int shared = 0;
  for (int i = 0; i < a.planes; ++i)
    for (int j = 0; j < b.planes; ++j)
      if (std::abs(dot(a.normal[i], b.normal[j])) > kSamePlane &&
          std::abs(dot(sub(b.point[j], a.point[i]), a.normal[i])) < tolerance) {
        if (which) which[shared] = i;
        ++shared;
        break;
      }
  return shared;
}

}  // namespace

std::vector<float> estimate_point_normals(const PointIndex& points, unsigned threads) {
  const size_t n = points.points().size();
  std::vector<float> out(3 * n);
  // Per point and independent: each piece writes only its own points.
  detail::split_ranges(n, threads, [&](size_t from, size_t to) {
    for (size_t i = from; i < to; ++i) {
      const V3 nn = robust_normal(points, static_cast<uint32_t>(i));
      for (int a = 0; a < 3; ++a) out[3 * i + a] = static_cast<float>(nn[a]);
    }
  });
  return out;
}

void align_to_features(TriangleMesh& m, const PointIndex& points, const CreaseOptions& o, AlignStats* stats,
                       std::vector<std::array<uint32_t, 2>>* chains, std::vector<uint32_t>* corners_out) {
  if (chains) chains->clear();
  if (corners_out) corners_out->clear();
  AlignStats st;
  if (!(o.angle_degrees > 0) || m.triangle_count() == 0 || points.points().size() == 0) {
    if (stats) *stats = st;
    return;
  }
  uint32_t n = static_cast<uint32_t>(m.vertex_count());
  const double min_cos = std::cos(o.angle_degrees * kPi / 180);
  // Triangles at each vertex.
  std::vector<uint32_t> offset(n + 1, 0), at;
  for (uint32_t v : m.triangles) ++offset[v + 1];
  for (uint32_t v = 0; v < n; ++v) offset[v + 1] += offset[v];
  at.resize(offset[n]);
  {
    std::vector<uint32_t> fill(offset.begin(), offset.end() - 1);
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) at[fill[m.triangles[3 * f + k]]++] = f;
  }
  std::vector<double> shortest(n, INFINITY), mean_edge(n, 0);
  std::vector<uint32_t> edges(n, 0);
  for (uint32_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t u = m.triangles[3 * f + k], w = m.triangles[3 * f + (k + 1) % 3];
      const double l = std::sqrt(dot(sub(pos(m, u), pos(m, w)), sub(pos(m, u), pos(m, w))));
      shortest[u] = std::min(shortest[u], l), shortest[w] = std::min(shortest[w], l);
      mean_edge[u] += l, mean_edge[w] += l, ++edges[u], ++edges[w];
    }

  // 1. What the points show around each vertex, at QEM's positions.
  PointNormals normals(points);
  std::vector<Feature> feature(n);
  std::vector<uint32_t> near;
  for (uint32_t v = 0; v < n; ++v) {
    if (edges[v] == 0) continue;
    feature[v] = classify(points, normals, pos(m, v), 0.6 * mean_edge[v] / edges[v], min_cos, o, near);
    st.line_vertices += feature[v].planes == 2;
    st.corner_vertices += feature[v].planes == 3;
  }

  // 2. Moves onto the features: corners first, then the vertices nearest
  // their line (each move judged against the moves already made).
  std::vector<uint32_t> order;
  std::vector<double> move(n, INFINITY);
  for (uint32_t v = 0; v < n; ++v)
    if (feature[v].planes) {
      move[v] = std::sqrt(dot(sub(feature[v].target, pos(m, v)), sub(feature[v].target, pos(m, v))));
      // A vertex with a null edge has no scale to judge its move by (and
      // move / 0 would put a NaN in the sort's comparisons): left alone.
      if (!(shortest[v] > 0)) continue;
      if (move[v] <= (feature[v].planes == 3 ? kCornerReach : kLineReach) * mean_edge[v] / edges[v]) order.push_back(v);
    }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if (feature[a].planes != feature[b].planes) return feature[a].planes > feature[b].planes;
    if (move[a] / shortest[a] != move[b] / shortest[b]) return move[a] / shortest[a] < move[b] / shortest[b];
    return a < b;
  });
  std::vector<uint8_t> snapped(n, 0), refused(n, 0);
  std::vector<V3> corners;  // taken: a second vertex on one corner would make a null edge
  const auto try_snap = [&](uint32_t v, double min_quality) {
    const Feature& f = feature[v];
    if (f.planes == 3) {
      bool taken = false;
      for (const V3& c : corners) taken = taken || dot(sub(c, f.target), sub(c, f.target)) < std::pow(0.25 * shortest[v], 2);
      if (taken) return;
    }
    const V3 old = pos(m, v);
    bool ok = true;
    std::vector<V3> old_normals;
    for (uint32_t j = offset[v]; j < offset[v + 1]; ++j) old_normals.push_back(unit(face_normal(m, at[j])));
    for (int a = 0; a < 3; ++a) m.positions[3 * size_t{v} + a] = static_cast<float>(f.target[a]);
    for (uint32_t j = offset[v]; j < offset[v + 1] && ok; ++j) {
      const uint32_t t = at[j];
      const double q = quality(pos(m, m.triangles[3 * t]), pos(m, m.triangles[3 * t + 1]), pos(m, m.triangles[3 * t + 2]));
      ok = q > min_quality && dot(unit(face_normal(m, t)), old_normals[j - offset[v]]) > 0;
    }
    if (!ok) {
      for (int a = 0; a < 3; ++a) m.positions[3 * size_t{v} + a] = static_cast<float>(old[a]);
      refused[v] = 1;
      return;
    }
    snapped[v] = 1, refused[v] = 0;
    ++st.snapped;
    if (f.planes == 3 && corners_out) corners_out->push_back(v);
    if (f.planes == 3) corners.push_back(f.target);
  };
  for (uint32_t v : order) try_snap(v, kMinQuality);
  // 2a. Gaps (CreaseOptions::gap_snaps): a line vertex whose move was
  // refused, where the chain along its line stops at it (vertices of its
  // ring moved onto the line on one side of it at most) and goes on again
  // within kGapSpan of its edges on the other side, is tried once more with
  // the floor kGapQuality.  QEM leaves two or three vertices beside a line
  // there, each move making a sliver with the next (the roof at seed 3: a
  // 0.17 stretch of its vertical edge without a vertex on it, moves refused
  // at quality 0.140, 0.119 and 0.147, the edge rounded by the butterfly:
  // level-3 Hausdorff distance 2.25% of the diagonal).  Only where the line
  // goes on: retried beside every line's end too, with nothing to join,
  // the fandisk's level-3 error rose 18% over three seeds.
  if (o.gap_snaps)
    for (uint32_t v : order) {
      if (!refused[v] || feature[v].planes != 2) continue;
      const double len = mean_edge[v] / edges[v];
      bool ahead = false, behind = false;
      for (uint32_t j = offset[v]; j < offset[v + 1]; ++j)
        for (int k = 0; k < 3; ++k) {
          const uint32_t x = m.triangles[3 * at[j] + k];
          if (x == v || !snapped[x] || shared_planes(feature[v], feature[x], 0.1 * len) < 2) continue;
          const double s = dot(sub(pos(m, x), feature[v].target), feature[v].dir);
          ahead = ahead || s > 0, behind = behind || s < 0;
        }
      if (ahead && behind) continue;
      // A vertex on the line (within a tenth of an edge of it) on an open side.
      bool beyond = false;
      for (uint32_t x = 0; x < n && !beyond; ++x) {
        if (x == v || !snapped[x] || feature[x].planes != 2) continue;
        const V3 d = sub(pos(m, x), feature[v].target);
        const double s = dot(d, feature[v].dir);
        if ((s > 0 ? ahead : behind) || std::abs(s) > kGapSpan * len || dot(d, d) - s * s > 0.01 * len * len) continue;
        beyond = shared_planes(feature[v], feature[x], 0.1 * len) >= 2;
      }
      if (beyond) try_snap(v, kGapQuality);
    }

  // 2b. Collapses: a vertex QEM left beside a line (or a corner) whose move
  // onto it was refused, because a vertex of the line next to it is already
  // there and the move would make a sliver, is merged into that neighbour.
  // Left, it is a dart: the chain along the line breaks at it and the
  // butterfly rounds the feature there on every level (the cube: 51 of its
  // 82 darts were such vertices).
  if (o.collapse) {
    std::vector<std::vector<uint32_t>> tris(n);
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) tris[m.triangles[3 * f + k]].push_back(f);
    std::vector<uint8_t> dead_triangle(m.triangle_count(), 0), alive(n, 1);
    std::vector<uint32_t> ring_v, ring_u, common;
    for (uint32_t v = 0; v < n; ++v) {
      if (snapped[v] || !feature[v].planes || !alive[v]) continue;
      if (!(move[v] <= (feature[v].planes == 3 ? kCornerReach : kLineReach) * mean_edge[v] / edges[v])) continue;
      sorted_ring(m, tris[v], v, ring_v);
      if (ring_v.size() != tris[v].size()) continue;  // on a boundary
      // The neighbour on v's line (or corner) nearest v.
      uint32_t best = n;
      double best_d = INFINITY;
      for (uint32_t u : ring_v) {
        if (!snapped[u] || !alive[u]) continue;
        const V3 d = sub(pos(m, u), pos(m, v));
        const double len = std::sqrt(dot(d, d));
        if (shared_planes(feature[v], feature[u], 0.1 * len + 0.1 * move[v]) < 2) continue;
        if (len < best_d) best_d = len, best = u;
      }
      if (best == n) continue;
      const uint32_t u = best;
      sorted_ring(m, tris[u], u, ring_u);
      if (ring_u.size() != tris[u].size()) continue;
      common.clear();
      std::set_intersection(ring_v.begin(), ring_v.end(), ring_u.begin(), ring_u.end(), std::back_inserter(common));
      if (common.size() != 2) continue;  // the link condition: else the collapse pinches the surface
      bool ok = tris[common[0]].size() > 3 && tris[common[1]].size() > 3 && tris[u].size() + tris[v].size() - 4 <= kMaxValence;
      // v's other triangles, with u in v's place: not turned, not tilted
      // off their plane, not slivers.
      for (size_t j = 0; j < tris[v].size() && ok; ++j) {
        const uint32_t f = tris[v][j];
        bool has_u = false;
        V3 p[3];
        for (int k = 0; k < 3; ++k) {
          const uint32_t x = m.triangles[3 * f + k];
          has_u = has_u || x == u;
          p[k] = pos(m, x == v ? u : x);
        }
        if (has_u) continue;
        const V3 before = unit(face_normal(m, f)), after = unit(cross(sub(p[1], p[0]), sub(p[2], p[0])));
        ok = dot(before, after) > kKeepNormal && quality(p[0], p[1], p[2]) > kMinQuality;
      }
      if (!ok) continue;
      for (uint32_t f : tris[v]) {
        bool has_u = false;
        for (int k = 0; k < 3; ++k) has_u = has_u || m.triangles[3 * f + k] == u;
        if (has_u) {
          dead_triangle[f] = 1;
          for (int k = 0; k < 3; ++k) {
            auto& list = tris[m.triangles[3 * f + k]];
            if (m.triangles[3 * f + k] != v) list.erase(std::find(list.begin(), list.end(), f));
          }
          continue;
        }
        for (int k = 0; k < 3; ++k)
          if (m.triangles[3 * f + k] == v) m.triangles[3 * f + k] = u;
        tris[u].push_back(f);
      }
      tris[v].clear();
      alive[v] = 0;
      ++st.collapses;
    }
    if (st.collapses) {
      // Renumber: the survivors keep their order, the merged triangles go.
      std::vector<uint32_t> id(n, 0);
      uint32_t next = 0;
      for (uint32_t v = 0; v < n; ++v)
        if (alive[v]) {
          id[v] = next;
          for (int a = 0; a < 3; ++a) m.positions[3 * size_t{next} + a] = m.positions[3 * size_t{v} + a];
          feature[next] = feature[v], snapped[next] = snapped[v];
          ++next;
        }
      m.positions.resize(3 * size_t{next});
      feature.resize(next), snapped.resize(next);
      size_t kept = 0;
      for (uint32_t f = 0; f < dead_triangle.size(); ++f)
        if (!dead_triangle[f]) {
          for (int k = 0; k < 3; ++k) m.triangles[3 * kept + k] = id[m.triangles[3 * f + k]];
          ++kept;
        }
      m.triangles.resize(3 * kept);
      if (corners_out)
        for (uint32_t& c : *corners_out) c = id[c];
      n = next;
    }
  }

  // 2c. Relaxation on the flat faces: a vertex whose triangles all lie in
  // one plane (within kFlatFan) moves, in that plane, towards its
  // neighbours' mean.  The surface is the same; the triangles next to a
  // line get the size of their neighbours.  QEM leaves short edges along a
  // feature and long ones across the flat face beside it, and the
  // butterfly's stencil there reaches across the face and puts odd
  // vertices past the feature line, in the face's plane, where no
  // displacement along the normal can bring them back (the cube: 0.13
  // outside, its Hausdorff distance).  With relax_beside_lines, a vertex
  // whose points show a line but which was not moved onto it moves too when
  // its own triangles are flat: such vertices carry the worst rings (the
  // cube's worst: valence 8, 4 neighbours 0.07-0.3 away towards the line,
  // 4 0.9-1.7 away across the face).
  const auto relax_flat = [&]() {
    std::vector<std::vector<uint32_t>> tris(n);
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) tris[m.triangles[3 * f + k]].push_back(f);
    std::vector<uint32_t> ring;
    for (int round = 0; round < kRelaxRounds; ++round)
      for (uint32_t v = 0; v < n; ++v) {
        if (snapped[v] || (feature[v].planes && !o.relax_beside_lines) || tris[v].size() < 3) continue;
        const V3 nv = unit(face_normal(m, tris[v][0]));
        bool flat = true;
        for (uint32_t f : tris[v]) flat = flat && dot(unit(face_normal(m, f)), nv) > kFlatFan;
        if (!flat) continue;
        sorted_ring(m, tris[v], v, ring);
        if (ring.size() != tris[v].size()) continue;  // on a boundary
        const V3 pv = pos(m, v);
        if (feature[v].planes) {
          // Beside a line: only a fan flat within kFlatBeside (within
          // kFlatFan the fandisk's and the cylinder's errors rose 7-34%).
          bool tight = true;
          for (uint32_t f : tris[v]) tight = tight && dot(unit(face_normal(m, f)), nv) > kFlatBeside;
          if (!tight) continue;
        }
        V3 mean{0, 0, 0};
        for (uint32_t x : ring)
          for (int a = 0; a < 3; ++a) mean[a] += pos(m, x)[a] / double(ring.size());
        V3 d = sub(mean, pv);
        const double h = dot(d, nv);
        for (int a = 0; a < 3; ++a) d[a] = 0.5 * (d[a] - h * nv[a]);  // in the plane, half way
        std::vector<double> before;
        for (uint32_t f : tris[v]) {
          const uint32_t* t = &m.triangles[3 * f];
          before.push_back(quality(pos(m, t[0]), pos(m, t[1]), pos(m, t[2])));
        }
        for (int a = 0; a < 3; ++a) m.positions[3 * size_t{v} + a] = static_cast<float>(pv[a] + d[a]);
        // Kept when no triangle turns over and the worst one gets no worse.
        bool ok = true;
        double worst_before = INFINITY, worst_after = INFINITY;
        for (size_t j = 0; j < tris[v].size(); ++j) {
          const uint32_t* t = &m.triangles[3 * tris[v][j]];
          const double q = quality(pos(m, t[0]), pos(m, t[1]), pos(m, t[2]));
          ok = ok && dot(unit(face_normal(m, tris[v][j])), nv) > (feature[v].planes ? kFlatBeside : kFlatFan);
          worst_before = std::min(worst_before, before[j]), worst_after = std::min(worst_after, q);
        }
        if (!ok || worst_after < worst_before)
          for (int a = 0; a < 3; ++a) m.positions[3 * size_t{v} + a] = static_cast<float>(pv[a]);
        else
          ++st.relaxed;
      }
  };
  if (o.relax && st.snapped > 0) relax_flat();

  // 3. Flips: an edge c-d whose two triangles' far corners u, w lie on one
  // line (two planes in common, the segment along them) becomes u-w, so
  // the line runs along control edges instead of zig-zagging across them.
  const auto chain = [&](uint32_t u, uint32_t w) {
    if (!snapped[u] || !snapped[w]) return false;
    const V3 d = sub(pos(m, w), pos(m, u));
    const double len = std::sqrt(dot(d, d));
    if (!(len > 0)) return false;
    int which[3];
    if (shared_planes(feature[u], feature[w], 0.1 * len, which) < 2) return false;
    for (int s = 0; s < 2; ++s)
      if (std::abs(dot(d, feature[u].normal[which[s]])) > kAlong * len) return false;
    return true;
  };
  std::unordered_map<uint64_t, uint32_t> edge;
  std::vector<int> valence(n, 0);
  for (uint32_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      edge[key(m.triangles[3 * f + k], m.triangles[3 * f + (k + 1) % 3])] = f;
      ++valence[m.triangles[3 * f + k]];  // triangles at a vertex: its valence on a closed mesh
    }
  const auto third = [&](uint32_t f, uint32_t a, uint32_t b) {
    for (int k = 0; k < 3; ++k)
      if (m.triangles[3 * f + k] != a && m.triangles[3 * f + k] != b) return m.triangles[3 * f + k];
    return a;
  };
  // The flip of edge c-d of triangles f = (c, d, u) and g = (d, c, w) to
  // u-w: f becomes (u, c, w), g (w, d, u); the edge map and valences follow,
  // and `tris` (each vertex's triangles) when given: f leaves d for w, g
  // leaves c for u.  Steps 3 and 3b differ only in which edges they flip.
  const auto flip_edge = [&](uint32_t f, uint32_t g, uint32_t c, uint32_t d, uint32_t u, uint32_t w,
                             std::vector<std::vector<uint32_t>>* tris) {
    edge.erase(key(c, d)), edge.erase(key(d, c));
    m.triangles[3 * f] = u, m.triangles[3 * f + 1] = c, m.triangles[3 * f + 2] = w;
    m.triangles[3 * g] = w, m.triangles[3 * g + 1] = d, m.triangles[3 * g + 2] = u;
    edge[key(u, c)] = f, edge[key(c, w)] = f, edge[key(w, u)] = f;
    edge[key(w, d)] = g, edge[key(d, u)] = g, edge[key(u, w)] = g;
    --valence[c], --valence[d], ++valence[u], ++valence[w];
    if (tris) {
      auto& t = *tris;
      t[d].erase(std::find(t[d].begin(), t[d].end(), f)), t[c].erase(std::find(t[c].begin(), t[c].end(), g));
      t[w].push_back(f), t[u].push_back(g);
    }
  };
  for (int pass = 0; pass < 4; ++pass) {
    size_t flips = 0;
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) {
        const uint32_t c = m.triangles[3 * f + k], d = m.triangles[3 * f + (k + 1) % 3];
        const auto twin = edge.find(key(d, c));
        if (twin == edge.end()) continue;
        const uint32_t g = twin->second, u = third(f, c, d), w = third(g, c, d);
        if (u == w || edge.count(key(u, w)) || edge.count(key(w, u))) continue;
        if (valence[c] <= 3 || valence[d] <= 3 || chain(c, d) || !chain(u, w)) continue;
        const V3 pu = pos(m, u), pw = pos(m, w), pc = pos(m, c), pd = pos(m, d);
        const V3 old = unit(V3{face_normal(m, f)[0] + face_normal(m, g)[0], face_normal(m, f)[1] + face_normal(m, g)[1],
                               face_normal(m, f)[2] + face_normal(m, g)[2]});
        if (quality(pu, pc, pw) < 0.05 || quality(pw, pd, pu) < 0.05) continue;
        if (dot(unit(cross(sub(pc, pu), sub(pw, pu))), old) <= 0 || dot(unit(cross(sub(pd, pw), sub(pu, pw))), old) <= 0) continue;
        flip_edge(f, g, c, d, u, w, nullptr);
        ++flips;
        k = 3;  // f changed: on to the next triangle
      }
    st.flips += flips;
    if (flips == 0) break;
  }
  // 3b. Flips toward valence 6 on the flat faces beside a line: an edge
  // c-d whose two triangles lie in one plane (within kFlatFan), not a
  // chain edge, with a vertex that sees a line among c, d and the far
  // corners u, w, becomes u-w when that brings the four vertices' valences
  // closer to regular (see dev below) and leaves no triangle turned or
  // poorer than kMinQuality (or than the pair's worst before).  The surface
  // is the same (the quad is flat); what changes is the butterfly's
  // stencil beside the line: QEM leaves valence 8-10 vertices there with
  // lopsided rings (a few short edges towards the line, a few long ones
  // across the face), and the extraordinary rule's negative weights on the
  // far ones put odd vertices past the line in the face's plane (the cube:
  // 0.128 outside, its Hausdorff distance).  Measured (crease_bench.md,
  // ninth session): alone the flips raise the cube's level 3 (+48%, seed
  // 1); with relax_beside_lines and the relaxation run again after them,
  // the cube, roof and fandisk fall over three seeds.
  if (o.valence_flips && st.snapped > 0) {
    std::vector<uint8_t> boundary(n, 0);
    for (const auto& [uv, f] : edge)
      if (!edge.count(key(static_cast<uint32_t>(uv), static_cast<uint32_t>(uv >> 32))))
        boundary[uv >> 32] = 1, boundary[static_cast<uint32_t>(uv)] = 1;
    // A vertex on a line counts only its triangles on this face's side
    // (regular: 3, as a boundary vertex's); a corner's sectors are left to
    // themselves; any other vertex counts all of them (regular: 6).  A
    // cube's face with many vertices along its edges and few inside must
    // otherwise give the inside ones valence 8-10.
    std::vector<std::vector<uint32_t>> tris(n);
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) tris[m.triangles[3 * f + k]].push_back(f);
    const auto dev = [&](uint32_t x, int change, const V3& face) {
      if (snapped[x] && feature[x].planes == 3) return 0;
      if (!snapped[x]) return std::abs(valence[x] + change - 6);
      int side = 0;
      for (uint32_t t : tris[x]) side += dot(unit(face_normal(m, t)), face) > kSameSide;
      return std::abs(side + change - 3);
    };
    for (int pass = 0; pass < 8; ++pass) {
      size_t flips = 0;
      for (uint32_t f = 0; f < m.triangle_count(); ++f)
        for (int k = 0; k < 3; ++k) {
          const uint32_t c = m.triangles[3 * f + k], d = m.triangles[3 * f + (k + 1) % 3];
          const auto twin = edge.find(key(d, c));
          if (twin == edge.end()) continue;
          const uint32_t g = twin->second, u = third(f, c, d), w = third(g, c, d);
          if (u == w || edge.count(key(u, w)) || edge.count(key(w, u))) continue;
          if (boundary[c] || boundary[d] || boundary[u] || boundary[w] || valence[c] <= 4 || valence[d] <= 4) continue;
          if (!feature[c].planes && !feature[d].planes && !feature[u].planes && !feature[w].planes) continue;
          const V3 nf = unit(face_normal(m, f)), ng = unit(face_normal(m, g));
          if (dot(nf, ng) <= kFlatFan || chain(c, d)) continue;
          const int before = dev(c, 0, nf) + dev(d, 0, nf) + dev(u, 0, nf) + dev(w, 0, nf);
          const int after = dev(c, -1, nf) + dev(d, -1, nf) + dev(u, 1, nf) + dev(w, 1, nf);
          if (after >= before) continue;
          const V3 pu = pos(m, u), pw = pos(m, w), pc = pos(m, c), pd = pos(m, d);
          const double worst = std::min(quality(pc, pd, pu), quality(pd, pc, pw));
          const double q1 = quality(pu, pc, pw), q2 = quality(pw, pd, pu);
          if (std::min(q1, q2) < std::min(worst, kMinQuality)) continue;
          if (dot(unit(cross(sub(pc, pu), sub(pw, pu))), nf) <= 0 || dot(unit(cross(sub(pd, pw), sub(pu, pw))), nf) <= 0) continue;
          flip_edge(f, g, c, d, u, w, &tris);
          ++flips;
          k = 3;
        }
      st.valence_flips += flips;
      if (flips == 0) break;
    }
    if (st.valence_flips && o.relax && o.relax_after_flips) relax_flat();
  }

  // 4. Splits: where a line stops at a vertex (a dart) because no vertex
  // lies on it further on, the edge it crosses next is split at the line,
  // and the walk goes on from the new vertex until it meets a vertex of
  // the line (or a corner) next to it.  Capped at a tenth of the vertices.
  if (o.split) {
    std::vector<std::vector<uint32_t>> tris(m.vertex_count());
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) tris[m.triangles[3 * f + k]].push_back(f);
    const size_t cap = m.vertex_count() / 10;
    const auto drop = [&](uint32_t v, uint32_t f) { tris[v].erase(std::find(tris[v].begin(), tris[v].end(), f)); };
    const auto add_triangle = [&](uint32_t f, uint32_t a, uint32_t b, uint32_t c) {
      if (f == m.triangle_count()) m.triangles.insert(m.triangles.end(), {a, b, c});
      else m.triangles[3 * f] = a, m.triangles[3 * f + 1] = b, m.triangles[3 * f + 2] = c;
      edge[key(a, b)] = f, edge[key(b, c)] = f, edge[key(c, a)] = f;
    };
    const uint32_t first = static_cast<uint32_t>(m.vertex_count());
    for (uint32_t start = 0; start < first && st.splits < cap; ++start) {
      if (!snapped[start] || feature[start].planes != 2) continue;
      for (double sign : {1.0, -1.0}) {
        uint32_t u = start;
        for (int steps = 0; steps < 16 && st.splits < cap; ++steps) {
          const V3 dir = {sign * feature[start].dir[0], sign * feature[start].dir[1], sign * feature[start].dir[2]};
          const V3 pu = pos(m, u);
          // Done when the line goes on along an edge of u already.
          bool joined = false;
          for (uint32_t f : tris[u])
            for (int k = 0; k < 3; ++k) {
              const uint32_t v = m.triangles[3 * f + k];
              if (v != u && chain(u, v) && dot(sub(pos(m, v), pu), dir) > 0) joined = true;
            }
          if (joined) break;
          // The triangle at u whose far edge the line crosses.
          uint32_t best_f = 0, c = 0, d = 0;
          double best_gap = INFINITY, best_s = 0;
          for (uint32_t f : tris[u]) {
            int k = 0;
            while (m.triangles[3 * f + k] != u) ++k;
            const uint32_t a = m.triangles[3 * f + (k + 1) % 3], b = m.triangles[3 * f + (k + 2) % 3];
            // Closest points of the line u + s dir and the segment a + l (b - a).
            const V3 pa = pos(m, a), ab = sub(pos(m, b), pa), ua = sub(pa, pu);
            const double bb = dot(ab, ab), db = dot(dir, ab), den = bb - db * db;
            if (!(den > 1e-12 * bb)) continue;
            const double l = (db * dot(dir, ua) - dot(ab, ua)) / den;
            if (l < 0.2 || l > 0.8) continue;
            const double s = dot(dir, ua) + l * db;
            const V3 gap = sub(V3{pa[0] + l * ab[0], pa[1] + l * ab[1], pa[2] + l * ab[2]}, V3{pu[0] + s * dir[0], pu[1] + s * dir[1], pu[2] + s * dir[2]});
            const double g = std::sqrt(dot(gap, gap));
            if (s > 0 && g < 0.5 * std::sqrt(bb) && g < best_gap) best_gap = g, best_f = f, c = a, d = b, best_s = s;
          }
          if (!std::isfinite(best_gap)) break;
          const auto twin = edge.find(key(d, c));
          if (twin == edge.end() || chain(c, d)) break;
          const uint32_t f = best_f, g = twin->second, w = third(g, c, d);
          const V3 px = {pu[0] + best_s * dir[0], pu[1] + best_s * dir[1], pu[2] + best_s * dir[2]};
          const V3 pc = pos(m, c), pd = pos(m, d), pw = pos(m, w);
          const V3 nf = unit(face_normal(m, f)), ng = unit(face_normal(m, g));
          // The four new triangles: not slivers, not turned over.
          if (quality(pc, px, pu) < 0.05 || quality(px, pd, pu) < 0.05 || quality(pd, px, pw) < 0.05 || quality(px, pc, pw) < 0.05) break;
          if (dot(unit(cross(sub(px, pc), sub(pu, pc))), nf) <= 0 || dot(unit(cross(sub(pd, px), sub(pu, px))), nf) <= 0 ||
              dot(unit(cross(sub(px, pd), sub(pw, pd))), ng) <= 0 || dot(unit(cross(sub(pc, px), sub(pw, px))), ng) <= 0)
            break;
          // f = (c, d, u) -> (c, x, u) + (x, d, u); g = (d, c, w) -> (d, x, w) + (x, c, w).
          const uint32_t x = static_cast<uint32_t>(m.vertex_count());
          for (int a = 0; a < 3; ++a) m.positions.push_back(static_cast<float>(px[a]));
          feature.push_back(feature[start]);
          snapped.push_back(1);
          valence.push_back(4);
          ++valence[u], ++valence[w];
          tris.emplace_back();
          edge.erase(key(c, d)), edge.erase(key(d, c));
          const uint32_t f2 = static_cast<uint32_t>(m.triangle_count());
          add_triangle(f, c, x, u);
          add_triangle(f2, x, d, u);
          const uint32_t g2 = static_cast<uint32_t>(m.triangle_count());
          add_triangle(g, d, x, w);
          add_triangle(g2, x, c, w);
          drop(d, f), tris[d].push_back(f2), tris[u].push_back(f2);
          drop(c, g), tris[c].push_back(g2), tris[w].push_back(g2);
          tris[x] = {f, f2, g, g2};
          ++st.splits;
          u = x;
        }
      }
    }
  }
  if (chains) {
    chains->clear();
    for (const auto& [uv, f] : edge) {
      const uint32_t u = static_cast<uint32_t>(uv >> 32), w = static_cast<uint32_t>(uv);
      if (u < w && edge.count(key(w, u)) && chain(u, w)) chains->push_back({u, w});
    }
    std::sort(chains->begin(), chains->end());
  }
  if (stats) *stats = st;
}

}  // namespace dbss
