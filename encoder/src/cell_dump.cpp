#include "dbss/encoder/cell_dump.h"

#include <cstdio>
#include <map>
#include <string>

#include "dbss/io/file.h"

namespace dbss {

namespace {
void append_vertex(std::string& out, double x, double y, double z) {
  char b[96];
  const int n = std::snprintf(b, sizeof b, "v %.9g %.9g %.9g\n", x, y, z);
  out.append(b, static_cast<size_t>(n));
}
Status put(const std::string& path, const std::string& text) {
  return io::write_file_atomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}
}  // namespace

Status write_cells_obj(const std::string& path, const CellGrid& g, bool occupied_only) {
  auto in = [&](int i, int j, int k) {
    const uint8_t s = g.state[g.index(i, j, k)];
    return occupied_only ? s == CellGrid::kOccupied : s != CellGrid::kAir;
  };
  std::map<std::array<int, 3>, uint32_t> ids;
  std::string verts, faces;
  auto vid = [&](int i, int j, int k) {
    auto [it, fresh] = ids.try_emplace({i, j, k}, static_cast<uint32_t>(ids.size() + 1));
    if (fresh) append_vertex(verts, g.origin[0] + i * g.cell, g.origin[1] + j * g.cell, g.origin[2] + k * g.cell);
    return it->second;
  };
  static const int kUp[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  static const int kDown[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  for (int k = 1; k + 1 < g.n[2]; ++k)
    for (int j = 1; j + 1 < g.n[1]; ++j)
      for (int i = 1; i + 1 < g.n[0]; ++i) {
        if (!in(i, j, k)) continue;
        const int c[3] = {i, j, k};
        for (int a = 0; a < 3; ++a)
          for (int side = 0; side < 2; ++side) {
            int nb[3] = {i, j, k};
            nb[a] += side ? 1 : -1;
            if (in(nb[0], nb[1], nb[2])) continue;
            const int b = (a + 1) % 3, d = (a + 2) % 3;
            const auto& order = side ? kUp : kDown;
            faces.append("f");
            for (int q = 0; q < 4; ++q) {
              int p[3];
              p[a] = c[a] + side, p[b] = c[b] + order[q][0], p[d] = c[d] + order[q][1];
              faces.append(" ").append(std::to_string(vid(p[0], p[1], p[2])));
            }
            faces.append("\n");
          }
      }
  std::string out = "# dbss cells\n";
  out.append(verts).append(faces);
  return put(path, out);
}

}  // namespace dbss
