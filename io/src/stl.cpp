// STL, ascii or binary: triangle corners read (duplicates merged); binary written.
#include "formats.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include "text.h"

namespace dbss::io_detail {

// STL stores each triangle's corners: equal corners become one vertex
// (vertices in lexicographic order of their coordinates) and every corner
// three in a row a triangle of them.
static GeometryFile merge_corners(const std::vector<float>& corners) {
  using P = std::array<float, 3>;
  if (corners.empty()) return {};
  std::vector<P> p(corners.size() / 3);
  std::memcpy(p.data(), corners.data(), corners.size() * sizeof(float));
  std::vector<P> unique = p;
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  GeometryFile g;
  g.points.xyz.assign(&unique.data()->front(), &unique.data()->front() + 3 * unique.size());
  g.triangles.reserve(p.size());
  for (const P& x : p)
    g.triangles.push_back(static_cast<uint32_t>(std::lower_bound(unique.begin(), unique.end(), x) - unique.begin()));
  return g;
}

Result<GeometryFile> parse_stl(const std::string& name, std::string_view bytes) {
  PointCloud c;
  // Binary STL: an 80-byte header, a triangle count, 50 bytes per triangle.
  // Some binary files also start with "solid", so the size decides.
  if (bytes.size() >= 84) {
    const auto* u = reinterpret_cast<const unsigned char*>(bytes.data());
    const uint32_t n = uint32_t{u[80]} | uint32_t{u[81]} << 8 | uint32_t{u[82]} << 16 | uint32_t{u[83]} << 24;
    if (84 + 50 * uint64_t{n} == bytes.size()) {
      c.xyz.reserve(9 * size_t{n});
      for (uint32_t f = 0; f < n; ++f) {
        const char* t = bytes.data() + 84 + 50 * size_t{f} + 12;
        for (int k = 0; k < 3; ++k) {
          float v[3];
          std::memcpy(v, t + 12 * k, 12);
          const double d[3] = {v[0], v[1], v[2]};
          if (!push_point(c.xyz, d))
            return bad(name, "byte " + std::to_string(84 + 50 * size_t{f} + 12 + 12 * k) + ": coordinate is NaN or infinite");
        }
      }
      return merge_corners(c.xyz);
    }
  }
  if (bytes.substr(0, 5) != "solid")
    return bad(name, "neither ASCII STL (no 'solid') nor binary STL (size does not match the triangle count)");
  Lines lines(bytes);
  std::string_view line;
  while (lines.next(line)) {
    Tokens t(line);
    std::string_view tok;
    if (!t.next(tok) || tok != "vertex") continue;
    double v[3];
    for (int k = 0; k < 3; ++k)
      if (!t.next(tok) || !parse_double(tok, v[k])) return bad(name, at_line(lines.number()) + ": a vertex needs three numbers");
    if (!push_point(c.xyz, v)) return bad(name, at_line(lines.number()) + ": coordinate is NaN, infinite or over 1e15");
  }
  if (c.size() % 3 != 0)
    return bad(name, "ASCII STL has " + std::to_string(c.size()) + " vertex lines, not three per facet");
  return merge_corners(c.xyz);
}

// Binary: 80-byte header, triangle count, then per triangle a zero normal
// (readers recompute it), three corners and a zero attribute word.
Result<std::string> write_stl(const TriangleMesh& m) {
  std::string out(80, ' ');
  out.replace(0, 4, "dbss");
  auto u32 = [&](uint32_t u) {
    const char le[4] = {char(u), char(u >> 8), char(u >> 16), char(u >> 24)};
    out.append(le, 4);
  };
  u32(static_cast<uint32_t>(m.triangle_count()));
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    for (int k = 0; k < 3; ++k) u32(0);
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) u32(std::bit_cast<uint32_t>(m.positions[3 * m.triangles[3 * f + k] + a]));
    out.append(2, '\0');
  }
  return out;
}

}  // namespace dbss::io_detail
