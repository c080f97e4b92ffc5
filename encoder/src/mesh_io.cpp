#include "dbss/encoder/mesh_io.h"

#include <bit>
#include <cctype>
#include <cstdio>
#include <map>
#include <string>

#include "dbss/format/writer.h"

namespace dbss {

namespace {
void append_vertex(std::string& out, double x, double y, double z) {
  char b[96];
  const int n = std::snprintf(b, sizeof b, "v %.9g %.9g %.9g\n", x, y, z);
  out.append(b, static_cast<size_t>(n));
}
Status put(const std::string& path, const std::string& text) {
  return format::write_file_atomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}
}  // namespace

Status write_obj(const std::string& path, const TriangleMesh& m) {
  std::string out = "# dbss\n";
  for (size_t v = 0; v < m.vertex_count(); ++v) append_vertex(out, m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]);
  for (size_t f = 0; f < m.triangle_count(); ++f)
  {
    char b[64];
    const int n = std::snprintf(b, sizeof b, "f %u %u %u\n", m.triangles[3 * f] + 1, m.triangles[3 * f + 1] + 1,
                                m.triangles[3 * f + 2] + 1);
    out.append(b, static_cast<size_t>(n));
  }
  return put(path, out);
}

Status write_mesh(const std::string& path, const TriangleMesh& m) {
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".obj") return write_obj(path, m);
  if (ext == ".off") {
    std::string out = "OFF\n" + std::to_string(m.vertex_count()) + " " + std::to_string(m.triangle_count()) + " 0\n";
    char b[96];
    for (size_t v = 0; v < m.vertex_count(); ++v) {
      const int n = std::snprintf(b, sizeof b, "%.9g %.9g %.9g\n", m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]);
      out.append(b, static_cast<size_t>(n));
    }
    for (size_t f = 0; f < m.triangle_count(); ++f) {
      const int n = std::snprintf(b, sizeof b, "3 %u %u %u\n", m.triangles[3 * f], m.triangles[3 * f + 1], m.triangles[3 * f + 2]);
      out.append(b, static_cast<size_t>(n));
    }
    return put(path, out);
  }
  if (ext == ".ply") {
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment dbss\nelement vertex " + std::to_string(m.vertex_count()) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(m.triangle_count()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
    auto raw = [&](const void* p, size_t n) { out.append(static_cast<const char*>(p), n); };
    for (float x : m.positions) {
      const uint32_t u = std::bit_cast<uint32_t>(x);
      const uint8_t le[4] = {uint8_t(u), uint8_t(u >> 8), uint8_t(u >> 16), uint8_t(u >> 24)};
      raw(le, 4);
    }
    for (size_t f = 0; f < m.triangle_count(); ++f) {
      const uint8_t three = 3;
      raw(&three, 1);
      for (int k = 0; k < 3; ++k) {
        const uint32_t u = m.triangles[3 * f + k];
        const uint8_t le[4] = {uint8_t(u), uint8_t(u >> 8), uint8_t(u >> 16), uint8_t(u >> 24)};
        raw(le, 4);
      }
    }
    return put(path, out);
  }
  if (ext == ".stl") {
    std::string out(80, ' ');
    out.replace(0, 4, "dbss");
    auto u32 = [&](uint32_t u) {
      const char le[4] = {char(u), char(u >> 8), char(u >> 16), char(u >> 24)};
      out.append(le, 4);
    };
    u32(static_cast<uint32_t>(m.triangle_count()));
    for (size_t f = 0; f < m.triangle_count(); ++f) {
      for (int k = 0; k < 3; ++k) u32(0);  // normal: readers recompute it
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) u32(std::bit_cast<uint32_t>(m.positions[3 * m.triangles[3 * f + k] + a]));
      out.append(2, '\0');
    }
    return put(path, out);
  }
  return Status(ErrorCode::invalid_argument, path + ": unknown mesh format (expected .ply, .obj, .off or .stl)");
}

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
