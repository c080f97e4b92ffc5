#include "dbss/encoder/self_intersections.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

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

}  // namespace dbss
