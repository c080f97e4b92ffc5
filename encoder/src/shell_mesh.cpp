#include "dbss/encoder/shell_mesh.h"

#include <string>

namespace dbss {

namespace {
constexpr uint32_t kNoVertex = 0xFFFFFFFFu;
}  // namespace

Result<TriangleMesh> triangulate_shell(const CellGrid& g, bool collapse_types) {
  const int nx = g.n[0] + 1, ny = g.n[1] + 1, nz = g.n[2] + 1;
  std::vector<uint32_t> corner_id(size_t(nx) * ny * nz, kNoVertex);
  TriangleMesh m;
  auto vertex = [&](int i, int j, int k) {
    uint32_t& id = corner_id[(size_t(k) * ny + j) * nx + i];
    if (id == kNoVertex) {
      id = static_cast<uint32_t>(m.vertex_count());
      m.positions.push_back(static_cast<float>(g.origin[0] + i * g.cell));
      m.positions.push_back(static_cast<float>(g.origin[1] + j * g.cell));
      m.positions.push_back(static_cast<float>(g.origin[2] + k * g.cell));
    }
    return id;
  };
  for (int k = 1; k + 1 < g.n[2]; ++k)
    for (int j = 1; j + 1 < g.n[1]; ++j)
      for (int i = 1; i + 1 < g.n[0]; ++i) {
        if (!g.solid(i, j, k)) continue;
        const int c[3] = {i, j, k};
        for (int a = 0; a < 3; ++a)
          for (int side = 0; side < 2; ++side) {
            int nb[3] = {i, j, k};
            nb[a] += side ? 1 : -1;
            if (g.solid(nb[0], nb[1], nb[2])) continue;
            // Quad on the plane x_a = c[a] + side, counter-clockwise seen from the air.
            const int b = (a + 1) % 3, d = (a + 2) % 3;
            // (b, d) offsets: counter-clockwise about +a for the upper face,
            // reversed for the lower one, since e_b x e_d = e_a.
            static const int kUp[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            static const int kDown[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
            const auto& order = side ? kUp : kDown;
            int corners[4][3];
            for (int q = 0; q < 4; ++q) {
              corners[q][a] = c[a] + side;
              corners[q][b] = c[b] + order[q][0];
              corners[q][d] = c[d] + order[q][1];
            }
            uint32_t v[4];
            for (int q = 0; q < 4; ++q) v[q] = vertex(corners[q][0], corners[q][1], corners[q][2]);
            m.triangles.insert(m.triangles.end(), {v[0], v[1], v[2], v[0], v[2], v[3]});
          }
      }
  (void)collapse_types;
  const MeshInfo info = mesh_info(m);
  if (!info.manifold || !info.closed)
    return Status(ErrorCode::internal, "shell triangulation is not a closed manifold: " +
                                           (info.manifold ? std::string("it has a boundary") : info.status.message()));
  return m;
}

}  // namespace dbss
