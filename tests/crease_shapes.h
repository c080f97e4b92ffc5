// Test shapes with sharp features, and their true crease tags from the
// dihedral angles of the mesh (a mesh input gives them directly).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/format/container.h"

namespace dbss::test {

// The tagged edges of a control mesh as sorted vertex pairs (independent
// of the edge numbering, which flips and collapses change).
using Pairs = std::set<std::pair<uint32_t, uint32_t>>;
inline Pairs tagged_pairs(const LevelTopology& t, const format::Creases& tags) {
  Pairs out;
  for (uint32_t e = 0; e < t.edge_count(); ++e)
    if (tags.edge[e]) {
      const uint32_t u = t.triangles[t.edge_half[e]], w = t.triangles[next_half(t.edge_half[e])];
      out.insert({std::min(u, w), std::max(u, w)});
    }
  return out;
}

// The unit cube [-1, 1]^3: 8 vertices, 12 triangles (each face split along
// one diagonal), counter-clockwise from outside.
inline TriangleMesh cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.insert(m.positions.end(), {i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f});
  m.triangles = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  return m;
}

// A closed cylinder of radius 1 from z = -h to z = h: `sides` vertices per
// ring, `rings` >= 2 rings, a centre vertex per flat cap.
inline TriangleMesh capped_cylinder(uint32_t sides, uint32_t rings, float h = 1.0f) {
  TriangleMesh m;
  const double pi = 3.14159265358979323846;
  for (uint32_t r = 0; r < rings; ++r)
    for (uint32_t s = 0; s < sides; ++s) {
      const double a = 2 * pi * s / sides;
      m.positions.insert(m.positions.end(), {float(std::cos(a)), float(std::sin(a)), -h + 2 * h * r / (rings - 1)});
    }
  const uint32_t bottom = rings * sides, top = bottom + 1;
  m.positions.insert(m.positions.end(), {0.f, 0.f, -h, 0.f, 0.f, h});
  for (uint32_t r = 0; r + 1 < rings; ++r)
    for (uint32_t s = 0; s < sides; ++s) {
      const uint32_t a = r * sides + s, b = r * sides + (s + 1) % sides, c = a + sides, d = b + sides;
      m.triangles.insert(m.triangles.end(), {a, b, d, a, d, c});
    }
  for (uint32_t s = 0; s < sides; ++s) {
    m.triangles.insert(m.triangles.end(), {bottom, (s + 1) % sides, s});
    const uint32_t t0 = (rings - 1) * sides;
    m.triangles.insert(m.triangles.end(), {top, t0 + s, t0 + (s + 1) % sides});
  }
  return m;
}

// A fandisk-like machined part: a box under a ridge roof of two slopes
// meeting along a sharp edge (x = 0), built from an n x n grid per side
// (n even) so every face has interior vertices.  Flat faces, creases at
// 45 to 90 degrees, corners where three creases meet, and gable end faces
// whose rim kinks at the ridge.
inline TriangleMesh roof_block(uint32_t n = 4) {
  // A height field over [-1,1]^2 for the roof and a box under it, stitched
  // as one closed mesh through a grid on each of the 6 sides.
  TriangleMesh m;
  auto roof = [](double x, double) { return 0.5 + 0.5 * (1 - std::abs(x)); };
  // Build as a deformed cube grid: points of the subdivided cube surface
  // mapped so that the top face becomes the roof.
  std::vector<uint32_t> index;
  const auto vid = [&](int i, int j, int k) -> uint32_t& { return index[(size_t(i) * (n + 1) + j) * (n + 1) + k]; };
  index.assign(size_t(n + 1) * (n + 1) * (n + 1), 0xFFFFFFFFu);
  const auto add = [&](int i, int j, int k) {
    uint32_t& id = vid(i, j, k);
    if (id == 0xFFFFFFFFu) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n, z01 = double(k) / n;
      const double z = -1 + z01 * (1 + roof(x, y));
      id = static_cast<uint32_t>(m.positions.size() / 3);
      m.positions.insert(m.positions.end(), {float(x), float(y), float(z)});
    }
    return id;
  };
  const int N = static_cast<int>(n);
  // Each face of the cube grid as quads split along one diagonal, oriented outward.
  const auto quad = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d) {  // counter-clockwise a b c d
    m.triangles.insert(m.triangles.end(), {a, b, c, a, c, d});
  };
  for (int u = 0; u < N; ++u)
    for (int v = 0; v < N; ++v) {
      quad(add(u, v, 0), add(u, v + 1, 0), add(u + 1, v + 1, 0), add(u + 1, v, 0));  // z = min, facing -z
      quad(add(u, v, N), add(u + 1, v, N), add(u + 1, v + 1, N), add(u, v + 1, N));  // top
      quad(add(0, u, v), add(0, u, v + 1), add(0, u + 1, v + 1), add(0, u + 1, v));  // x = -1
      quad(add(N, u, v), add(N, u + 1, v), add(N, u + 1, v + 1), add(N, u, v + 1));  // x = +1
      quad(add(u, 0, v), add(u + 1, 0, v), add(u + 1, 0, v + 1), add(u, 0, v + 1));  // y = -1
      quad(add(u, N, v), add(u, N, v + 1), add(u + 1, N, v + 1), add(u + 1, N, v));  // y = +1
    }
  return m;  // only the surface's grid points were added
}

// Crease tags from the mesh itself: an edge is a crease where its two
// triangles' normals differ by more than `degrees`; a vertex with three or
// more crease edges is a corner.
inline format::Creases creases_from_dihedral(const TriangleMesh& m, double degrees) {
  auto t = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles).value();
  const auto normal = [&](uint32_t f, double n[3]) {
    const float* a = &m.positions[3 * size_t{m.triangles[3 * f]}];
    const float* b = &m.positions[3 * size_t{m.triangles[3 * f + 1]}];
    const float* c = &m.positions[3 * size_t{m.triangles[3 * f + 2]}];
    const double e[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double g[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    n[0] = e[1] * g[2] - e[2] * g[1], n[1] = e[2] * g[0] - e[0] * g[2], n[2] = e[0] * g[1] - e[1] * g[0];
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) n[k] /= l;
  };
  format::Creases c;
  c.edge.assign(t.edge_count(), 0);
  c.corner.assign(t.vertex_count, 0);
  std::vector<uint32_t> count(t.vertex_count, 0);
  const double limit = std::cos(degrees * 3.14159265358979323846 / 180);
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t h = t.edge_half[e], o = t.twin[h];
    if (o == kNoHalfEdge) continue;
    double a[3], b[3];
    normal(h / 3, a), normal(o / 3, b);
    if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < limit) {
      c.edge[e] = 1;
      ++count[t.triangles[h]], ++count[t.triangles[next_half(h)]];
    }
  }
  for (uint32_t v = 0; v < t.vertex_count; ++v) c.corner[v] = count[v] >= 3;
  return c;
}

}  // namespace dbss::test
