#include "dbss/encoder/mesh_ops.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "dbss/encoder/triangle_tree.h"

namespace dbss {

namespace {
using V3 = std::array<double, 3>;
V3 pos(const TriangleMesh& m, uint32_t v) { return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]}; }
V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
// The mean of v's neighbours' positions (false: v has none).
bool neighbour_mean(const TriangleMesh& m, const Adjacency& adj, uint32_t v, float out[3]) {
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
bool smoothing_target(const TriangleMesh& m, const Adjacency& adj, const Rim& rim, uint32_t v, float out[3]) {
  if (rim[v][0] == kNotOnRim) return neighbour_mean(m, adj, v, out);
  for (int a = 0; a < 3; ++a)
    out[a] = static_cast<float>(0.5 * (double{m.positions[3 * size_t{rim[v][0]} + a]} + m.positions[3 * size_t{rim[v][1]} + a]));
  return true;
}
V3 face_normal(const TriangleMesh& m, size_t f) {
  const V3 a = pos(m, m.triangles[3 * f]), b = pos(m, m.triangles[3 * f + 1]), c = pos(m, m.triangles[3 * f + 2]);
  return cross(sub(b, a), sub(c, a));
}
}  // namespace

Adjacency vertex_adjacency(const TriangleMesh& m) {
  const size_t n = m.vertex_count();
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  pairs.reserve(m.triangles.size() * 2);
  for (size_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[3 * f + k], b = m.triangles[3 * f + (k + 1) % 3];
      pairs.push_back({a, b});
      pairs.push_back({b, a});
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  Adjacency adj;
  adj.offset.assign(n + 1, 0);
  for (auto& p : pairs) ++adj.offset[p.first + 1];
  for (size_t v = 0; v < n; ++v) adj.offset[v + 1] += adj.offset[v];
  adj.index.resize(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) adj.index[i] = pairs[i].second;
  return adj;
}

Adjacency vertex_triangles(const TriangleMesh& m) {
  Adjacency a;
  a.offset.assign(m.vertex_count() + 1, 0);
  for (uint32_t v : m.triangles) ++a.offset[v + 1];
  for (size_t v = 0; v < m.vertex_count(); ++v) a.offset[v + 1] += a.offset[v];
  a.index.resize(m.triangles.size());
  std::vector<uint32_t> fill(a.offset.begin(), a.offset.end() - 1);
  for (size_t c = 0; c < m.triangles.size(); ++c) a.index[fill[m.triangles[c]]++] = static_cast<uint32_t>(c / 3);
  return a;
}

bool move_keeps_orientation(const TriangleMesh& m, const Adjacency& vt, uint32_t v, const float to[3]) {
  // Each triangle around v must keep facing within 90 degrees of where it
  // faced and of the fan's mean normal; the second test stops a triangle
  // from turning over a little at a time across iterations.
  V3 fan{0, 0, 0};
  for (uint32_t i = vt.offset[v]; i < vt.offset[v + 1]; ++i) {
    const V3 n = face_normal(m, vt.index[i]);
    for (int a = 0; a < 3; ++a) fan[a] += n[a];
  }
  for (uint32_t i = vt.offset[v]; i < vt.offset[v + 1]; ++i) {
    const uint32_t f = vt.index[i];
    V3 before[3], after[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t w = m.triangles[3 * size_t{f} + k];
      before[k] = pos(m, w);
      after[k] = w == v ? V3{to[0], to[1], to[2]} : before[k];
    }
    const V3 n0 = cross(sub(before[1], before[0]), sub(before[2], before[0]));
    const V3 n1 = cross(sub(after[1], after[0]), sub(after[2], after[0]));
    // A triangle already at odds with its fan may move, as long as it does
    // not turn further against the fan.
    if (dot(n0, n1) <= 0 || (dot(fan, n1) <= 0 && dot(fan, n1) < dot(fan, n0))) return false;
  }
  return true;
}

bool folded_around(const TriangleMesh& m, const Adjacency& vt, uint32_t v, double max_angle_degrees) {
  const double limit = std::cos(max_angle_degrees * std::numbers::pi / 180);
  for (uint32_t i = vt.offset[v]; i < vt.offset[v + 1]; ++i) {
    const uint32_t f = vt.index[i];
    const V3 nf = face_normal(m, f);
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[3 * size_t{f} + k], b = m.triangles[3 * size_t{f} + (k + 1) % 3];
      for (uint32_t j = vt.offset[a]; j < vt.offset[a + 1]; ++j) {
        const uint32_t g = vt.index[j];
        if (g == f) continue;
        bool has_b = false;
        for (int c = 0; c < 3; ++c) has_b |= m.triangles[3 * size_t{g} + c] == b;
        if (!has_b) continue;
        const V3 ng = face_normal(m, g);
        const double l = std::sqrt(dot(nf, nf) * dot(ng, ng));
        if (l > 0 && dot(nf, ng) / l < limit) return true;
      }
    }
  }
  return false;
}

Rim rim_neighbours(const TriangleMesh& m) {
  std::vector<std::pair<uint32_t, uint32_t>> half;
  half.reserve(m.triangles.size());
  for (size_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) half.push_back({m.triangles[3 * f + k], m.triangles[3 * f + (k + 1) % 3]});
  std::sort(half.begin(), half.end());
  Rim rim(m.vertex_count(), {kNotOnRim, kNotOnRim});
  std::vector<uint32_t> ins(m.vertex_count(), 0), outs(m.vertex_count(), 0);
  for (const auto& [a, b] : half) {
    if (std::binary_search(half.begin(), half.end(), std::pair{b, a})) continue;  // interior edge
    rim[a][1] = b, rim[b][0] = a;
    ++outs[a], ++ins[b];
  }
  for (size_t v = 0; v < rim.size(); ++v)
    if ((ins[v] || outs[v]) && (ins[v] != 1 || outs[v] != 1)) rim[v] = {static_cast<uint32_t>(v), static_cast<uint32_t>(v)};
  return rim;
}

std::vector<std::array<double, 3>> vertex_normals(const TriangleMesh& m) {
  std::vector<V3> n(m.vertex_count(), V3{0, 0, 0});
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const V3 fn = face_normal(m, f);
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) n[m.triangles[3 * f + k]][a] += fn[a];
  }
  for (auto& v : n) {
    const double l = std::sqrt(dot(v, v));
    if (l > 0)
      for (double& x : v) x /= l;
  }
  return n;
}

std::vector<uint32_t> foldover_vertices(const TriangleMesh& m, double max_angle_degrees) {
  std::map<std::pair<uint32_t, uint32_t>, size_t> first;
  const double limit = std::cos(max_angle_degrees * std::numbers::pi / 180);
  std::vector<uint32_t> out;
  for (size_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[3 * f + k], b = m.triangles[3 * f + (k + 1) % 3];
      auto it = first.find({b, a});
      if (it == first.end()) {
        first[{a, b}] = f;
        continue;
      }
      const V3 n1 = face_normal(m, f), n2 = face_normal(m, it->second);
      const double l = std::sqrt(dot(n1, n1) * dot(n2, n2));
      if (l > 0 && dot(n1, n2) / l < limit) out.insert(out.end(), {a, b});
    }
  return out;
}

size_t count_foldovers(const TriangleMesh& m, double max_angle_degrees) {
  return foldover_vertices(m, max_angle_degrees).size() / 2;
}

size_t untangle_folds(TriangleMesh& m, int rounds) {
  const Adjacency adj = vertex_adjacency(m);
  const Rim rim = rim_neighbours(m);
  size_t met = 0;
  for (int round = 0; round < rounds; ++round) {
    const std::vector<uint32_t> folded = foldover_vertices(m);
    if (folded.empty()) break;
    met += folded.size() / 2;
    std::vector<uint32_t> ring;
    for (uint32_t v : folded) {
      ring.push_back(v);
      for (uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i) ring.push_back(adj.index[i]);
    }
    for (uint32_t v : ring) {  // in place: later vertices see earlier moves
      float to[3];
      if (smoothing_target(m, adj, rim, v, to))
        for (int a = 0; a < 3; ++a) m.positions[3 * size_t{v} + a] = to[a];
    }
  }
  return met;
}

SurfaceDistance points_to_mesh(const std::vector<float>& xyz, const TriangleMesh& m) {
  const TriangleTree tree(m);
  SurfaceDistance out;
  const size_t n = xyz.size() / 3;
  for (size_t i = 0; i < n; ++i) {
    const double p[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    const double d = tree.distance(p);
    out.mean += d;
    out.max = std::max(out.max, d);
  }
  if (n) out.mean /= n;
  return out;
}

PointPlane fit_plane(const PointCloud& pc, const uint32_t* indices, size_t count) {
  PointPlane out;
  if (count == 0) return out;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (size_t j = 0; j < count; ++j) c += Eigen::Vector3d(pc.xyz[3 * indices[j]], pc.xyz[3 * indices[j] + 1], pc.xyz[3 * indices[j] + 2]);
  c /= static_cast<double>(count);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t j = 0; j < count; ++j) {
    const Eigen::Vector3d d = Eigen::Vector3d(pc.xyz[3 * indices[j]], pc.xyz[3 * indices[j] + 1], pc.xyz[3 * indices[j] + 2]) - c;
    cov += d * d.transpose();
  }
  // The direction of least spread: the eigenvector of the smallest
  // eigenvalue (Eigen sorts them ascending).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d n = eig.eigenvectors().col(0);
  out.point = {c[0], c[1], c[2]};
  out.normal = {n[0], n[1], n[2]};
  return out;
}

SurfaceDistance vertices_to_points_surface(const std::vector<float>& xyz, const PointIndex& index) {
  const PointCloud& pc = index.points();
  SurfaceDistance out;
  const size_t n = xyz.size() / 3;
  uint32_t near[8];
  float d2[8];
  for (size_t i = 0; i < n; ++i) {
    const size_t k = index.nearest_k(&xyz[3 * i], 8, near, d2);
    const PointPlane plane = fit_plane(pc, near, k);
    const Eigen::Vector3d p(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    const Eigen::Vector3d c(plane.point[0], plane.point[1], plane.point[2]), nrm(plane.normal[0], plane.normal[1], plane.normal[2]);
    const double dist = std::abs((p - c).dot(nrm));
    out.mean += dist;
    out.max = std::max(out.max, dist);
  }
  if (n) out.mean /= n;
  return out;
}

namespace {
// Whether segment pq crosses triangle abc (strictly, up to rounding).
bool segment_hits_triangle(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) {
  const V3 n = cross(sub(b, a), sub(c, a));
  const double dp = dot(n, sub(p, a)), dq = dot(n, sub(q, a));
  if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || dp == dq) return false;
  const double t = dp / (dp - dq);
  const V3 x{p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])};
  // Inside test by same-side signs of the three edge normals.
  const double s1 = dot(n, cross(sub(b, a), sub(x, a)));
  const double s2 = dot(n, cross(sub(c, b), sub(x, b)));
  const double s3 = dot(n, cross(sub(a, c), sub(x, c)));
  return (s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0);
}
bool triangles_intersect(const V3 t[3], const V3 u[3]) {
  for (int k = 0; k < 3; ++k) {
    if (segment_hits_triangle(t[k], t[(k + 1) % 3], u[0], u[1], u[2])) return true;
    if (segment_hits_triangle(u[k], u[(k + 1) % 3], t[0], t[1], t[2])) return true;
  }
  return false;
}
}  // namespace

std::vector<std::pair<uint32_t, uint32_t>> self_intersections(const TriangleMesh& m) {
  const size_t nf = m.triangle_count();
  std::vector<std::pair<uint32_t, uint32_t>> hits;
  if (nf == 0) return hits;
  // Triangle bounds, and cubic bins about twice the mean bound's extent, so
  // a triangle falls into a handful of bins (counted, then filled: CSR).
  std::vector<float> box(6 * nf);
  V3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  double extent = 0;
  for (size_t f = 0; f < nf; ++f) {
    float* b = &box[6 * f];
    for (int a = 0; a < 3; ++a) {
      const float x = m.positions[3 * size_t{m.triangles[3 * f]} + a], y = m.positions[3 * size_t{m.triangles[3 * f + 1]} + a],
                  z = m.positions[3 * size_t{m.triangles[3 * f + 2]} + a];
      b[a] = std::min({x, y, z}), b[3 + a] = std::max({x, y, z});
      lo[a] = std::min(lo[a], double{b[a]}), hi[a] = std::max(hi[a], double{b[3 + a]});
      extent += b[3 + a] - b[a];
    }
  }
  double cell = std::max(2 * extent / (3.0 * nf), 1e-30);
  // At most about 4 bins per triangle overall, however the mesh is spread.
  int n[3];
  for (;;) {
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / cell) + 1);
    if (double(n[0]) * n[1] * n[2] <= 4.0 * nf + 64) break;
    cell *= 1.5;
  }
  auto bin_range = [&](size_t f, int b0[3], int b1[3]) {
    for (int a = 0; a < 3; ++a) {
      b0[a] = std::clamp(static_cast<int>((box[6 * f + a] - lo[a]) / cell), 0, n[a] - 1);
      b1[a] = std::clamp(static_cast<int>((box[6 * f + 3 + a] - lo[a]) / cell), 0, n[a] - 1);
    }
  };
  const size_t nbins = size_t(n[0]) * n[1] * n[2];
  std::vector<uint32_t> start(nbins + 1, 0), items;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t f = 0; f < nf; ++f) {
      int b0[3], b1[3];
      bin_range(f, b0, b1);
      for (int z = b0[2]; z <= b1[2]; ++z)
        for (int y = b0[1]; y <= b1[1]; ++y)
          for (int x = b0[0]; x <= b1[0]; ++x) {
            const size_t id = (size_t(z) * n[1] + y) * n[0] + x;
            if (pass == 0) ++start[id + 1];
            else items[start[id]++] = static_cast<uint32_t>(f);
          }
    }
    if (pass == 0) {
      for (size_t i = 0; i < nbins; ++i) start[i + 1] += start[i];
      items.resize(start[nbins]);
    }
  }
  // The fill pass moved each start to the next bin's; shift back.
  for (size_t i = nbins; i > 0; --i) start[i] = start[i - 1];
  start[0] = 0;
  for (size_t id = 0; id < nbins; ++id) {
    const int bx = static_cast<int>(id % n[0]), by = static_cast<int>((id / n[0]) % n[1]), bz = static_cast<int>(id / (size_t(n[0]) * n[1]));
    for (uint32_t i = start[id]; i < start[id + 1]; ++i)
      for (uint32_t j = i + 1; j < start[id + 1]; ++j) {
        const uint32_t f = items[i], g = items[j];
        const float* bf = &box[6 * size_t{f}];
        const float* bg = &box[6 * size_t{g}];
        bool apart = false;
        for (int a = 0; a < 3; ++a) apart |= bf[a] > bg[3 + a] || bg[a] > bf[3 + a];
        if (apart) continue;
        // Test each pair once: in the bin holding the low corner of the
        // overlap of the two bounds.
        const int ox = std::clamp(static_cast<int>((std::max(bf[0], bg[0]) - lo[0]) / cell), 0, n[0] - 1);
        const int oy = std::clamp(static_cast<int>((std::max(bf[1], bg[1]) - lo[1]) / cell), 0, n[1] - 1);
        const int oz = std::clamp(static_cast<int>((std::max(bf[2], bg[2]) - lo[2]) / cell), 0, n[2] - 1);
        if (ox != bx || oy != by || oz != bz) continue;
        bool shared = false;
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) shared |= m.triangles[3 * size_t{f} + k] == m.triangles[3 * size_t{g} + l];
        if (shared) continue;
        V3 t[3], u[3];
        for (int k = 0; k < 3; ++k) t[k] = pos(m, m.triangles[3 * size_t{f} + k]), u[k] = pos(m, m.triangles[3 * size_t{g} + k]);
        if (triangles_intersect(t, u)) hits.push_back({std::min(f, g), std::max(f, g)});
      }
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

size_t count_self_intersections(const TriangleMesh& m) { return self_intersections(m).size(); }

namespace {
// The distinct corners of the triangles in `pairs`, ascending.
std::vector<uint32_t> corners_of(const TriangleMesh& m, const std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
  std::vector<uint32_t> verts;
  for (const auto& [f, g] : pairs)
    for (uint32_t tri : {f, g})
      for (int k = 0; k < 3; ++k) verts.push_back(m.triangles[3 * size_t{tri} + k]);
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  return verts;
}
}  // namespace

size_t relax_self_intersections(TriangleMesh& m, int rounds) {
  size_t moved = 0;
  const Adjacency adj = vertex_adjacency(m);
  const Rim rim = rim_neighbours(m);
  for (int round = 0; round < rounds; ++round) {
    const auto crossing = self_intersections(m);
    if (crossing.empty()) break;
    const std::vector<uint32_t> verts = corners_of(m, crossing);
    // Jacobi: every listed vertex goes to its neighbours' mean as they were.
    std::vector<float> to(3 * verts.size(), 0.0f);
    std::vector<uint8_t> has(verts.size(), 0);
    for (size_t i = 0; i < verts.size(); ++i) has[i] = smoothing_target(m, adj, rim, verts[i], &to[3 * i]);
    for (size_t i = 0; i < verts.size(); ++i)
      if (has[i])
        for (int a = 0; a < 3; ++a) m.positions[3 * size_t{verts[i]} + a] = to[3 * i + a];
    moved += verts.size();
  }
  return moved;
}

size_t undo_self_intersections(TriangleMesh& m, const std::vector<float>& safe, int rounds) {
  size_t reverted = 0;
  for (int round = 0; round <= rounds; ++round) {
    const auto crossing = self_intersections(m);
    if (crossing.empty()) return reverted;
    if (round == rounds) {
      // Still crossing after every local undo: all the way back.
      for (size_t i = 0; i < m.positions.size(); i += 3)
        reverted += m.positions[i] != safe[i] || m.positions[i + 1] != safe[i + 1] || m.positions[i + 2] != safe[i + 2];
      m.positions = safe;
      return reverted;
    }
    // The first rounds take the crossing triangles' vertices half way back,
    // which often suffices and keeps most of the moves; later rounds all
    // the way.
    const std::vector<uint32_t> verts = corners_of(m, crossing);
    const bool halfway = round < rounds / 2;
    for (uint32_t v : verts) {
      float* p = &m.positions[3 * size_t{v}];
      const float* b = &safe[3 * size_t{v}];
      if (p[0] == b[0] && p[1] == b[1] && p[2] == b[2]) continue;
      ++reverted;
      for (int a = 0; a < 3; ++a) p[a] = halfway ? 0.5f * (p[a] + b[a]) : b[a];
    }
  }
  return reverted;
}

bool inside_mesh(const TriangleMesh& m, const std::array<double, 3>& p) {
  // Sum of signed solid angles (Van Oosterom-Strackee): 4π inside, 0 outside.
  double total = 0;
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const V3 a = sub(pos(m, m.triangles[3 * f]), p), b = sub(pos(m, m.triangles[3 * f + 1]), p),
             c = sub(pos(m, m.triangles[3 * f + 2]), p);
    const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
    const double num = dot(a, cross(b, c));
    const double den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    total += 2 * std::atan2(num, den);
  }
  return total > 2 * std::numbers::pi;
}

}  // namespace dbss
