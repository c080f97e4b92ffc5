#include "dbss/encoder/self_intersections.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>

#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

namespace {
// Whether segment pq, whose ends lie dp and dq along the (unnormalised)
// normal n of triangle abc from a, crosses the triangle (strictly, up to
// rounding).
bool segment_hits_triangle(const V3& p, const V3& q, double dp, double dq, const V3& n, const V3& a, const V3& b,
                           const V3& c) {
  if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || dp == dq) return false;
  const double t = dp / (dp - dq);
  const V3 x{p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])};
  // Inside test by same-side signs of the three edge normals.
  const double s1 = dot(n, cross(sub(b, a), sub(x, a)));
  const double s2 = dot(n, cross(sub(c, b), sub(x, b)));
  const double s3 = dot(n, cross(sub(a, c), sub(x, c)));
  return (s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0);
}
// Whether an edge of one triangle crosses the other.  Each corner's side of
// the other triangle's plane is computed once (the same products the edge
// tests use, so the answer is theirs): a triangle strictly on one side of
// the other's plane has no edge through it, which settles most pairs of
// neighbouring triangles before any edge is tested.
bool triangles_intersect(const V3 t[3], const V3 u[3]) {
  const V3 nt = cross(sub(t[1], t[0]), sub(t[2], t[0])), nu = cross(sub(u[1], u[0]), sub(u[2], u[0]));
  double du[3], dt[3];
  for (int k = 0; k < 3; ++k) du[k] = dot(nt, sub(u[k], t[0])), dt[k] = dot(nu, sub(t[k], u[0]));
  const auto one_side = [](const double d[3]) {
    return (d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0);
  };
  const bool u_apart = one_side(du), t_apart = one_side(dt);
  if (u_apart && t_apart) return false;
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if (!t_apart && segment_hits_triangle(t[k], t[l], dt[k], dt[l], nu, u[0], u[1], u[2])) return true;
    if (!u_apart && segment_hits_triangle(u[k], u[l], du[k], du[l], nt, t[0], t[1], t[2])) return true;
  }
  return false;
}
// A triangle's bounds as floats (low x, y, z, then high).
void bounds(const TriangleMesh& m, size_t f, float b[6]) {
  for (int a = 0; a < 3; ++a) {
    const float x = m.positions[3 * size_t{m.triangles[3 * f]} + a], y = m.positions[3 * size_t{m.triangles[3 * f + 1]} + a],
                z = m.positions[3 * size_t{m.triangles[3 * f + 2]} + a];
    b[a] = std::min({x, y, z}), b[3 + a] = std::max({x, y, z});
  }
}
// Whether triangles f and g, their bounds overlapping, share no corner and
// cross.  (triangles_intersect is symmetric: every edge of each is tried
// against the other, so the order of f and g does not matter.)
bool pair_crosses(const TriangleMesh& m, size_t f, size_t g) {
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l)
      if (m.triangles[3 * f + k] == m.triangles[3 * g + l]) return false;
  V3 t[3], u[3];
  for (int k = 0; k < 3; ++k) t[k] = pos(m, m.triangles[3 * f + k]), u[k] = pos(m, m.triangles[3 * g + k]);
  return triangles_intersect(t, u);
}
bool overlap(const float p[6], const float q[6]) {
  for (int a = 0; a < 3; ++a)
    if (p[a] > q[3 + a] || q[a] > p[3 + a]) return false;
  return true;
}

// The crossing pairs with at least one marked triangle: the marked ones
// (a few dozen to a few thousand after a round of undo_crossings) are
// binned, and every triangle looks up the bins its bounds touch.  The same
// pairs as the full search restricted to them (bounds overlapping, no
// shared corner, crossing), without binning all the mesh's triangles into a
// grid of up to 16 bins per triangle: on the bunny 35k's 73k-triangle shell
// 3 ms a search, of which this takes a fraction.
std::vector<std::pair<uint32_t, uint32_t>> marked_crossings(const TriangleMesh& m, const std::vector<uint8_t>& marked) {
  const size_t nf = m.triangle_count();
  std::vector<std::pair<uint32_t, uint32_t>> hits;
  std::vector<uint32_t> ids;  // the marked triangles
  std::vector<float> box;     // their bounds
  float all[6] = {1e30f, 1e30f, 1e30f, -1e30f, -1e30f, -1e30f};  // the bounds of them all
  double extent = 0;
  for (size_t f = 0; f < nf; ++f) {
    if (!marked[f]) continue;
    ids.push_back(static_cast<uint32_t>(f));
    float b[6];
    bounds(m, f, b);
    for (int a = 0; a < 3; ++a) all[a] = std::min(all[a], b[a]), all[3 + a] = std::max(all[3 + a], b[3 + a]), extent += b[3 + a] - b[a];
    box.insert(box.end(), b, b + 6);
  }
  if (ids.empty()) return hits;
  double cell = std::max(3 * extent / (3.0 * ids.size()), 1e-30);
  int n[3];
  for (;;) {
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>((double{all[3 + a]} - all[a]) / cell) + 1);
    if (double(n[0]) * n[1] * n[2] <= 16.0 * ids.size() + 64) break;
    cell *= 1.5;
  }
  const double per_cell = 1 / cell;
  // Bins are clamped to the grid: a bound reaching past the marked ones'
  // still meets them in the bins at the grid's edge.
  const auto bin_range = [&](const float b[6], int b0[3], int b1[3]) {
    for (int a = 0; a < 3; ++a) {
      b0[a] = std::clamp(static_cast<int>((double{b[a]} - all[a]) * per_cell), 0, n[a] - 1);
      b1[a] = std::clamp(static_cast<int>((double{b[3 + a]} - all[a]) * per_cell), 0, n[a] - 1);
    }
  };
  const size_t nbins = size_t(n[0]) * n[1] * n[2];
  std::vector<uint32_t> start(nbins + 1, 0), items;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < ids.size(); ++i) {
      int b0[3], b1[3];
      bin_range(&box[6 * i], b0, b1);
      for (int z = b0[2]; z <= b1[2]; ++z)
        for (int y = b0[1]; y <= b1[1]; ++y)
          for (int x = b0[0]; x <= b1[0]; ++x) {
            const size_t id = (size_t(z) * n[1] + y) * n[0] + x;
            if (pass == 0) ++start[id + 1];
            else items[start[id]++] = static_cast<uint32_t>(i);
          }
    }
    if (pass == 0) {
      for (size_t i = 0; i < nbins; ++i) start[i + 1] += start[i];
      items.resize(start[nbins]);
    }
  }
  for (size_t i = nbins; i > 0; --i) start[i] = start[i - 1];
  start[0] = 0;
  // Per marked triangle, the last triangle that met it: a pair sharing
  // several bins is tried once.
  std::vector<uint32_t> met(ids.size(), UINT32_MAX);
  for (size_t g = 0; g < nf; ++g) {
    float b[6];
    bounds(m, g, b);
    if (!overlap(b, all)) continue;
    int b0[3], b1[3];
    bin_range(b, b0, b1);
    for (int z = b0[2]; z <= b1[2]; ++z)
      for (int y = b0[1]; y <= b1[1]; ++y)
        for (int x = b0[0]; x <= b1[0]; ++x) {
          const size_t id = (size_t(z) * n[1] + y) * n[0] + x;
          for (uint32_t i = start[id]; i < start[id + 1]; ++i) {
            const uint32_t k = items[i], f = ids[k];
            // Two marked triangles: tried from the higher one's side.
            if (met[k] == g || f == g || (marked[g] && f > g)) continue;
            met[k] = static_cast<uint32_t>(g);
            if (overlap(b, &box[6 * k]) && pair_crosses(m, f, g))
              hits.push_back({std::min<uint32_t>(f, static_cast<uint32_t>(g)), std::max<uint32_t>(f, static_cast<uint32_t>(g))});
          }
        }
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

// The crossing pairs; with `marked`, only pairs with at least one marked
// triangle are tried.
std::vector<std::pair<uint32_t, uint32_t>> crossings(const TriangleMesh& m, const std::vector<uint8_t>* marked) {
  const size_t nf = m.triangle_count();
  std::vector<std::pair<uint32_t, uint32_t>> hits;
  if (nf == 0) return hits;
  if (marked) return marked_crossings(m, *marked);
  // Triangle bounds, and cubic bins three times the mean bound's extent, so
  // a triangle falls into one to a few bins (counted, then filled: CSR).
  // (On the bunny's 73k-triangle shell: 1x took 2.3 times as long as 3x,
  // 2x 1.3 times, 4x and 6x about the same.)
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
  double cell = std::max(3 * extent / (3.0 * nf), 1e-30);
  // At most 16 bins per triangle overall, however the mesh is spread (a
  // surface fills a thin layer of the box: most bins stay empty).
  int n[3];
  for (;;) {
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / cell) + 1);
    if (double(n[0]) * n[1] * n[2] <= 16.0 * nf + 64) break;
    cell *= 1.5;
  }
  // By a product, not a quotient: bin ranges are computed some 20 times per
  // triangle and search, and the divisions were most of a search that
  // tries only marked triangles.  Any binning that grows with the
  // coordinate finds the same pairs.
  const double per_cell = 1 / cell;
  auto bin_range = [&](size_t f, int b0[3], int b1[3]) {
    for (int a = 0; a < 3; ++a) {
      b0[a] = std::clamp(static_cast<int>((box[6 * f + a] - lo[a]) * per_cell), 0, n[a] - 1);
      b1[a] = std::clamp(static_cast<int>((box[6 * f + 3 + a] - lo[a]) * per_cell), 0, n[a] - 1);
    }
  };
  const size_t nbins = size_t(n[0]) * n[1] * n[2];
  // Each triangle's lowest bin: the bin of the low corner of two bounds'
  // overlap is the larger of theirs, per axis (the bin is monotonic in the
  // coordinate), with no division per pair.
  std::vector<std::array<int, 3>> low(nf);
  for (size_t f = 0; f < nf; ++f) {
    int b1[3];
    bin_range(f, low[f].data(), b1);
  }
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
  // A bin's triangles are copied next to each other (bounds, lowest bin,
  // corners) before its pairs are tried: the pairs outnumber the triangles
  // sevenfold, and reading them scattered over the mesh's arrays cost more
  // than every test they go through.
  struct Item {
    float box[6];
    int low[3];
    uint32_t v[3];
    uint32_t f;
  };
  std::vector<Item> local;
  for (size_t id = 0; id < nbins; ++id) {
    if (start[id + 1] - start[id] < 2) continue;
    const int bx = static_cast<int>(id % n[0]), by = static_cast<int>((id / n[0]) % n[1]), bz = static_cast<int>(id / (size_t(n[0]) * n[1]));
    local.clear();
    for (uint32_t i = start[id]; i < start[id + 1]; ++i) {
      const uint32_t f = items[i];
      Item it;
      for (int a = 0; a < 6; ++a) it.box[a] = box[6 * size_t{f} + a];
      for (int a = 0; a < 3; ++a) it.low[a] = low[f][a], it.v[a] = m.triangles[3 * size_t{f} + a];
      it.f = f;
      local.push_back(it);
    }
    // Sorted by the bounds' low x, a triangle's pairs end at the first one
    // starting beyond its high x (sweep and prune): most pairs in a bin lie
    // apart in x, and are never looked at.  The hits are sorted below, so
    // the order pairs are found in does not matter.
    std::sort(local.begin(), local.end(), [](const Item& a, const Item& b) { return a.box[0] < b.box[0]; });
    for (size_t i = 0; i < local.size(); ++i)
      for (size_t j = i + 1; j < local.size() && !(local[j].box[0] > local[i].box[3]); ++j) {
        const Item& p = local[i];
        const Item& q = local[j];
        // Bounds apart in y or z; the pair tested in another bin (each pair
        // is tested once: in the bin holding the low corner of the overlap
        // of the two bounds); a corner shared.  Some 1M pairs per search of
        // the bunny 35k's shell get here and 2% go on: the three tests are
        // combined without branches, so the one branch left is predictable
        // (a branch per test, each taken at random, cost more than the
        // tests).
        bool skip = (p.box[1] > q.box[4]) | (q.box[1] > p.box[4]) | (p.box[2] > q.box[5]) | (q.box[2] > p.box[5]);
        const auto lx = std::max(p.low[0], q.low[0]), ly = std::max(p.low[1], q.low[1]), lz = std::max(p.low[2], q.low[2]);
        skip |= (lx != bx) | (ly != by) | (lz != bz);
        for (int k = 0; k < 3; ++k) skip |= (p.v[k] == q.v[0]) | (p.v[k] == q.v[1]) | (p.v[k] == q.v[2]);
        if (skip) continue;
        V3 t[3], u[3];
        for (int k = 0; k < 3; ++k) t[k] = pos(m, p.v[k]), u[k] = pos(m, q.v[k]);
        if (triangles_intersect(t, u)) hits.push_back({std::min(p.f, q.f), std::max(p.f, q.f)});
      }
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}
}  // namespace

std::vector<std::pair<uint32_t, uint32_t>> self_intersections(const TriangleMesh& m) { return crossings(m, nullptr); }

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

namespace {
// undo_self_intersections; with `only_moved`, the first search tries only
// triangles with a corner away from its `safe` position.
size_t undo_crossings(TriangleMesh& m, const std::vector<float>& safe, int rounds, bool only_moved) {
  size_t reverted = 0;
  // After the first round, a pair can cross only if a vertex of it moved
  // back in the last round or it crossed before that round (its corners
  // unmoved): only pairs with such a triangle are tried again, which finds
  // the same pairs as a full search at a fraction of its cost.
  std::vector<uint8_t> marked;
  std::vector<uint8_t> moved;
  std::vector<std::pair<uint32_t, uint32_t>> crossing;
  for (int round = 0; round <= rounds; ++round) {
    if (round == 0 && only_moved) {
      marked.assign(m.triangle_count(), 0);
      for (size_t f = 0; f < m.triangle_count(); ++f)
        for (int k = 0; k < 3; ++k) {
          const size_t v = m.triangles[3 * f + k];
          marked[f] |= m.positions[3 * v] != safe[3 * v] || m.positions[3 * v + 1] != safe[3 * v + 1] ||
                       m.positions[3 * v + 2] != safe[3 * v + 2];
        }
      crossing = crossings(m, &marked);
    } else if (round == 0) {
      crossing = self_intersections(m);
    } else {
      marked.assign(m.triangle_count(), 0);
      for (const auto& [f, g] : crossing) marked[f] = marked[g] = 1;
      for (size_t f = 0; f < m.triangle_count(); ++f)
        for (int k = 0; k < 3; ++k) marked[f] |= moved[m.triangles[3 * f + k]];
      crossing = crossings(m, &marked);
    }
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
    moved.assign(m.vertex_count(), 0);
    for (uint32_t v : verts) {
      float* p = &m.positions[3 * size_t{v}];
      const float* b = &safe[3 * size_t{v}];
      if (p[0] == b[0] && p[1] == b[1] && p[2] == b[2]) continue;
      ++reverted;
      moved[v] = 1;
      for (int a = 0; a < 3; ++a) p[a] = halfway ? 0.5f * (p[a] + b[a]) : b[a];
    }
  }
  return reverted;
}
}  // namespace

size_t undo_self_intersections(TriangleMesh& m, const std::vector<float>& safe, int rounds) {
  return undo_crossings(m, safe, rounds, false);
}

size_t undo_new_crossings(TriangleMesh& m, const std::vector<float>& safe, int rounds) {
  return undo_crossings(m, safe, rounds, true);
}

}  // namespace dbss
