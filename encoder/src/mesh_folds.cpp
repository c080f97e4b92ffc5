#include "dbss/encoder/mesh_folds.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

bool move_keeps_orientation(const TriangleMesh& m, const Adjacency& vt, uint32_t v, const float to[3]) {
  // Each triangle around v must keep facing within 90 degrees of where it
  // faced and of the fan's mean normal; the second test stops a triangle
  // from turning over a little at a time across iterations.
  // The fan's normals are kept for the test below (the same products it
  // computed a second time), for fans of up to kKept triangles.
  constexpr uint32_t kKept = 32;
  V3 kept[kKept];
  V3 fan{0, 0, 0};
  for (uint32_t i = vt.offset[v]; i < vt.offset[v + 1]; ++i) {
    const V3 n = face_normal(m, vt.index[i]);
    if (i - vt.offset[v] < kKept) kept[i - vt.offset[v]] = n;
    for (int a = 0; a < 3; ++a) fan[a] += n[a];
  }
  for (uint32_t i = vt.offset[v]; i < vt.offset[v + 1]; ++i) {
    const uint32_t f = vt.index[i];
    V3 after[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t w = m.triangles[3 * size_t{f} + k];
      after[k] = w == v ? V3{to[0], to[1], to[2]} : pos(m, w);
    }
    const V3 n0 = i - vt.offset[v] < kKept ? kept[i - vt.offset[v]] : face_normal(m, f);
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

namespace {
// The original definition, by a map of directed edges: kept for meshes
// where an edge has more than two triangles, whose answer depends on the
// map's overwrites.
std::vector<uint32_t> foldover_vertices_mapped(const TriangleMesh& m, double limit) {
  std::map<std::pair<uint32_t, uint32_t>, size_t> first;
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
}  // namespace

namespace {
// The mesh's edges as pairs of opposite half-edges (corners 3 * triangle +
// k), in the order of the undirected edge; empty with `mapped` set when an
// edge has more than two triangles or two of the same direction (see
// foldover_vertices_mapped).  Depends on the triangles only, so rounds that
// move vertices reuse it.
struct EdgeSides {
  bool mapped = false;
  std::vector<std::pair<uint32_t, uint32_t>> pairs;  // (first, second) corner
};
EdgeSides edge_sides(const TriangleMesh& m) {
  // Half-edges in the order of their undirected edge (low end, high end),
  // then of their corner: the two sides of an edge end up next to each
  // other.  Bucketed by the low end (a counting sort, corners ascending
  // within a bucket), then each bucket, a dozen half-edges, sorted by the
  // high end: the order one sort of all the half-edges by (edge, corner)
  // gave (a strict order, so any sort gives it), at a seventh of its cost
  // (16 ms a call on the bunny 35k's 73k-triangle shell).
  const size_t nc = m.triangles.size();
  uint32_t nv = 0;
  for (uint32_t v : m.triangles) nv = std::max(nv, v + 1);
  const auto ends = [&m](size_t c) {
    const uint32_t a = m.triangles[c], b = m.triangles[c - c % 3 + (c + 1) % 3];
    return std::pair<uint32_t, uint32_t>{std::min(a, b), std::max(a, b)};
  };
  std::vector<uint32_t> start(size_t{nv} + 1, 0);
  for (size_t c = 0; c < nc; ++c) ++start[ends(c).first + 1];
  for (uint32_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  // (high end, corner), the key within a bucket.
  std::vector<uint64_t> half(nc);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t c = 0; c < nc; ++c) {
      const auto [lo, hi] = ends(c);
      half[fill[lo]++] = uint64_t{hi} << 32 | c;
    }
  }
  for (uint32_t v = 0; v < nv; ++v) {
    uint64_t* b = half.data() + start[v];
    const size_t len = start[v + 1] - start[v];
    if (len > 32) {
      std::sort(b, b + len);
      continue;
    }
    for (size_t i = 1; i < len; ++i)  // insertion sort: buckets are short
      for (size_t j = i; j > 0 && b[j - 1] > b[j]; --j) std::swap(b[j - 1], b[j]);
  }
  EdgeSides out;
  out.pairs.reserve(nc / 2);
  for (uint32_t v = 0; v < nv; ++v)
    for (size_t i = start[v]; i < start[v + 1];) {
      size_t j = i + 1;
      while (j < start[v + 1] && half[j] >> 32 == half[i] >> 32) ++j;
      const uint32_t c0 = static_cast<uint32_t>(half[i]);
      // Opposite directions, as the map's lookup of the reverse edge needs.
      if (j - i > 2 || (j - i == 2 && m.triangles[c0] == m.triangles[static_cast<uint32_t>(half[i + 1])])) {
        out.mapped = true;
        out.pairs.clear();
        return out;
      }
      if (j - i == 2) out.pairs.push_back({c0, static_cast<uint32_t>(half[i + 1])});
      i = j;
    }
  return out;
}

std::vector<uint32_t> foldover_vertices(const TriangleMesh& m, const EdgeSides& sides, double limit) {
  if (sides.mapped) return foldover_vertices_mapped(m, limit);
  // The pairs are reported in the order the map version met their second
  // side (corner order), as it did.
  std::vector<uint32_t> later;  // corners of the second sides of folded edges
  for (const auto& [c0, c1] : sides.pairs) {
    const V3 n1 = face_normal(m, c1 / 3), n2 = face_normal(m, c0 / 3);
    const double l = std::sqrt(dot(n1, n1) * dot(n2, n2));
    if (l > 0 && dot(n1, n2) / l < limit) later.push_back(c1);
  }
  std::sort(later.begin(), later.end());
  std::vector<uint32_t> out(2 * later.size());
  for (size_t i = 0; i < later.size(); ++i) {
    const uint32_t c = later[i];
    out[2 * i] = m.triangles[c], out[2 * i + 1] = m.triangles[c - c % 3 + (c + 1) % 3];
  }
  return out;
}

double fold_limit(double max_angle_degrees) { return std::cos(max_angle_degrees * std::numbers::pi / 180); }
}  // namespace

std::vector<uint32_t> foldover_vertices(const TriangleMesh& m, double max_angle_degrees) {
  return foldover_vertices(m, edge_sides(m), fold_limit(max_angle_degrees));
}

size_t count_foldovers(const TriangleMesh& m, double max_angle_degrees) {
  return foldover_vertices(m, max_angle_degrees).size() / 2;
}

size_t untangle_folds(TriangleMesh& m, int rounds, bool coarse) {
  return untangle_folds(m, vertex_adjacency(m), rim_neighbours(m), rounds, coarse);
}

size_t untangle_folds(TriangleMesh& m, const Adjacency& adj, const Rim& rim, int rounds, bool coarse) {
  size_t met = 0;
  // The rounds move vertices only: the edges' sides are found once.
  const EdgeSides sides = edge_sides(m);
  const double limit = fold_limit(150);
  std::vector<uint32_t> folded = foldover_vertices(m, sides, limit);
  std::vector<uint32_t> ring;
  std::vector<float> was;
  for (int round = 0; round < rounds && !folded.empty(); ++round) {
    met += folded.size() / 2;
    ring.clear();
    for (uint32_t v : folded) {
      ring.push_back(v);
      if (!coarse)
        for (uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i) ring.push_back(adj.index[i]);
    }
    if (coarse) {
      was.resize(3 * ring.size());
      for (size_t i = 0; i < ring.size(); ++i)
        for (int a = 0; a < 3; ++a) was[3 * i + a] = m.positions[3 * size_t{ring[i]} + a];
    }
    for (uint32_t v : ring) {  // in place: later vertices see earlier moves
      float to[3];
      if (smoothing_target(m, adj, rim, v, to))
        for (int a = 0; a < 3; ++a) m.positions[3 * size_t{v} + a] = to[a];
    }
    if (!coarse && round + 1 == rounds) break;  // (the count after the last round is not needed)
    std::vector<uint32_t> now = foldover_vertices(m, sides, limit);
    if (coarse && now.size() > folded.size()) {
      // Backwards: a vertex listed twice gets back where it was first.
      for (size_t i = ring.size(); i-- > 0;)
        for (int a = 0; a < 3; ++a) m.positions[3 * size_t{ring[i]} + a] = was[3 * i + a];
      break;
    }
    folded = std::move(now);
  }
  return met;
}

}  // namespace dbss
