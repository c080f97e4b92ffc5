#include "dbss/encoder/shell_mesh.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace dbss {

namespace {
constexpr uint32_t kNoVertex = 0xFFFFFFFFu;
}  // namespace

Result<TriangleMesh> triangulate_shell(const CellGrid& g, bool collapse_types, MeshInfo* info_out) {
  const int nx = g.n[0] + 1, ny = g.n[1] + 1;
  // Vertex ids of the grid's corners, two planes of them: the cells of
  // layer k use the corners of planes k and k + 1 only, and the layers go
  // in order (plane k's ids are kept in slot k % 2).  A full grid of ids was
  // 4.7 MB on the bunny 35k's grid, allocated, cleared and faulted in for
  // each shell.
  const size_t plane = size_t(nx) * ny;
  std::vector<uint32_t> corner_id(2 * plane, kNoVertex);
  const auto id_at = [&](int i, int j, int k) -> uint32_t& { return corner_id[size_t(k & 1) * plane + size_t(j) * nx + i]; };
  std::vector<std::array<int, 3>> corner_of;  // grid corner of each vertex
  auto vertex = [&](int i, int j, int k) {
    uint32_t& id = id_at(i, j, k);
    if (id == kNoVertex) {
      id = static_cast<uint32_t>(corner_of.size());
      corner_of.push_back({i, j, k});
    }
    return id;
  };
  // A corner is an "air vertex" of a cell when that cell is the only solid
  // one of the eight around it: nothing else can use it.
  auto lone = [&](int i, int j, int k) {
    int solid = 0;
    for (int c = 0; c < 8; ++c) solid += g.solid(i - 1 + (c & 1), j - 1 + (c >> 1 & 1), k - 1 + (c >> 2));
    return solid == 1;
  };

  struct Quad {
    uint32_t v[4];
    int avoid = -1;  // corner the diagonal must not touch (Type 3)
  };
  std::vector<Quad> quads;
  std::vector<uint32_t> parent;  // union-find over vertices for collapses
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (int k = 1; k + 1 < g.n[2]; ++k) {
    // Plane k + 1 takes the slot of plane k - 1, which no later cell uses.
    std::fill_n(corner_id.begin() + std::ptrdiff_t((k + 1) & 1) * std::ptrdiff_t(plane), plane, kNoVertex);
    for (int j = 1; j + 1 < g.n[1]; ++j)
      for (int i = 1; i + 1 < g.n[0]; ++i) {
        if (!g.solid(i, j, k)) continue;
        const int c[3] = {i, j, k};
        const size_t first = quads.size();
        int solid_faces[2] = {-1, -1}, n_solid = 0;
        for (int a = 0; a < 3; ++a)
          for (int side = 0; side < 2; ++side) {
            int nb[3] = {i, j, k};
            nb[a] += side ? 1 : -1;
            if (g.solid(nb[0], nb[1], nb[2])) {
              if (n_solid < 2) solid_faces[n_solid] = 2 * a + side;
              ++n_solid;
              continue;
            }
            // Quad on the plane x_a = c[a] + side, counter-clockwise seen
            // from the air: (b, d) offsets run counter-clockwise about +a for
            // the upper face and the other way for the lower one, since
            // e_b x e_d = e_a.
            const int b = (a + 1) % 3, d = (a + 2) % 3;
            static const int kUp[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            static const int kDown[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
            const auto& order = side ? kUp : kDown;
            Quad q;
            for (int n = 0; n < 4; ++n) {
              int p[3];
              p[a] = c[a] + side;
              p[b] = c[b] + order[n][0];
              p[d] = c[d] + order[n][1];
              q.v[n] = vertex(p[0], p[1], p[2]);
            }
            quads.push_back(q);
          }
        if (parent.size() < corner_of.size()) {
          const size_t old = parent.size();
          parent.resize(corner_of.size());
          for (size_t x = old; x < parent.size(); ++x) parent[x] = static_cast<uint32_t>(x);
        }
        if (!collapse_types) continue;
        const int n_air = 6 - n_solid;
        // The cell's air vertices (at most its eight corners: kept on the
        // stack, not allocated per cell).
        std::array<uint32_t, 8> air_ids;
        size_t n_air_ids = 0;
        for (int cc = 0; cc < 8; ++cc) {
          const int p[3] = {i + (cc & 1), j + (cc >> 1 & 1), k + (cc >> 2)};
          if (lone(p[0], p[1], p[2])) air_ids[n_air_ids++] = id_at(p[0], p[1], p[2]);
        }
        const std::span<const uint32_t> air(air_ids.data(), n_air_ids);
        const bool ribbon = n_solid == 2 && solid_faces[0] / 2 == solid_faces[1] / 2;
        if ((n_air == 5 && air.size() == 4) || (n_air == 4 && !ribbon && air.size() == 2)) {
          // Types 1 and 2: the air vertices become one.
          for (size_t x = 1; x < air.size(); ++x) parent[find(air[x])] = find(air[0]);
        } else if (n_air == 3 && air.size() == 1) {
          // Type 3: split the three air quads away from the air vertex, so
          // it keeps one triangle per face.
          for (size_t qi = first; qi < quads.size(); ++qi)
            for (int n = 0; n < 4; ++n)
              if (quads[qi].v[n] == air[0]) quads[qi].avoid = n;
        }
      }
  }

  // Vertices: one per union-find class, at the mean of its corners.
  TriangleMesh m;
  std::vector<uint32_t> out_id(corner_of.size(), kNoVertex);
  std::vector<std::array<double, 4>> sum(corner_of.size(), {0, 0, 0, 0});
  for (uint32_t v = 0; v < corner_of.size(); ++v) {
    auto& s4 = sum[find(v)];
    for (int a = 0; a < 3; ++a) s4[a] += g.origin[a] + corner_of[v][a] * g.cell;
    s4[3] += 1;
  }
  auto emit = [&](uint32_t v) {
    const uint32_t r = find(v);
    if (out_id[r] == kNoVertex) {
      out_id[r] = static_cast<uint32_t>(m.vertex_count());
      for (int a = 0; a < 3; ++a) m.positions.push_back(static_cast<float>(sum[r][a] / sum[r][3]));
    }
    return out_id[r];
  };
  for (const Quad& q : quads) {
    uint32_t r[4];
    for (int n = 0; n < 4; ++n) r[n] = find(q.v[n]);
    // Corners left distinct after the collapses, in order.
    uint32_t d[4];
    int nd = 0;
    for (int n = 0; n < 4; ++n)
      if (r[n] != r[(n + 3) % 4]) d[nd++] = q.v[n];
    if (nd == 4) {
      const int s0 = q.avoid >= 0 ? (q.avoid + 1) % 4 : 0;  // the diagonal runs s0 -> s0 + 2
      const uint32_t a = emit(q.v[s0]), b = emit(q.v[(s0 + 1) % 4]), c = emit(q.v[(s0 + 2) % 4]),
                     e = emit(q.v[(s0 + 3) % 4]);
      m.triangles.insert(m.triangles.end(), {a, b, c, a, c, e});
    } else if (nd == 3) {
      m.triangles.insert(m.triangles.end(), {emit(d[0]), emit(d[1]), emit(d[2])});
    }
  }
  const MeshInfo info = mesh_info(m);
  if (!info.manifold || !info.closed)
    return Status(ErrorCode::internal, "shell triangulation is not a closed manifold: " +
                                           (info.manifold ? std::string("it has a boundary") : info.status.message()));
  // The boundary of a solid has twice the solid's Euler characteristic; the
  // collapses and diagonals must not change the topology the cells have.
  const int64_t solid = carving_shape(g).euler;
  if (info.euler != 2 * solid)
    return Status(ErrorCode::internal, "shell triangulation has Euler characteristic " + std::to_string(info.euler) +
                                           ", the carved solid's boundary " + std::to_string(2 * solid));
  if (info_out) *info_out = info;
  return m;
}

}  // namespace dbss
