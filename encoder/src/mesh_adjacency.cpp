#include "dbss/encoder/mesh_adjacency.h"

#include <algorithm>
#include <cmath>

#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

Adjacency vertex_adjacency(const TriangleMesh& m) {
  // Each vertex's neighbours from its fan, sorted and deduplicated per
  // vertex: the same lists as one sort of every (vertex, neighbour) pair,
  // at the cost of many sorts of a dozen.
  const size_t n = m.vertex_count();
  const Adjacency vt = vertex_triangles(m);
  Adjacency adj;
  adj.offset.assign(n + 1, 0);
  adj.index.reserve(m.triangles.size() * 2);
  std::vector<uint32_t> ring;
  for (size_t v = 0; v < n; ++v) {
    ring.clear();
    for (uint32_t i = vt.offset[v]; i < vt.offset[v + 1]; ++i) {
      const uint32_t* t = &m.triangles[3 * size_t{vt.index[i]}];
      // The corners joined to v by an edge of this triangle (both others,
      // or v itself where a triangle repeats a corner, as a pair (v, v)
      // would have recorded).
      for (int k = 0; k < 3; ++k)
        if (t[k] == v) ring.push_back(t[(k + 1) % 3]), ring.push_back(t[(k + 2) % 3]);
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    adj.index.insert(adj.index.end(), ring.begin(), ring.end());
    adj.offset[v + 1] = static_cast<uint32_t>(adj.index.size());
  }
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


Rim rim_neighbours(const TriangleMesh& m) {
  // A half-edge a->b is interior when a triangle at b runs b->a: looked up
  // in b's fan (a few triangles) rather than by sorting every half-edge.
  const Adjacency vt = vertex_triangles(m);
  const auto has_twin = [&](uint32_t a, uint32_t b) {
    for (uint32_t i = vt.offset[b]; i < vt.offset[b + 1]; ++i) {
      const uint32_t* t = &m.triangles[3 * size_t{vt.index[i]}];
      for (int k = 0; k < 3; ++k)
        if (t[k] == b && t[(k + 1) % 3] == a) return true;
    }
    return false;
  };
  Rim rim(m.vertex_count(), {kNotOnRim, kNotOnRim});
  std::vector<uint32_t> ins(m.vertex_count(), 0), outs(m.vertex_count(), 0);
  for (size_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[3 * f + k], b = m.triangles[3 * f + (k + 1) % 3];
      if (has_twin(a, b)) continue;  // interior edge
      // (Where several rim edges meet at a vertex the order of these
      // writes does not matter: the vertex is pinned below.)
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

}  // namespace dbss
