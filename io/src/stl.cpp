// STL, ascii or binary: triangle corners read (duplicates merged); binary written.
#include "formats.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include "text.h"

namespace dbss::io_detail {

static void merge_duplicates(std::vector<float>& xyz) {
  std::vector<std::array<float, 3>> p(xyz.size() / 3);
  std::memcpy(p.data(), xyz.data(), xyz.size() * sizeof(float));
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  xyz.assign(&p.data()->front(), &p.data()->front() + 3 * p.size());
}

Result<PointCloud> parse_stl(const std::string& name, std::string_view bytes) {
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
      merge_duplicates(c.xyz);
      return c;
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
  merge_duplicates(c.xyz);
  return c;
}

// Binary: 80-byte header, triangle count, then per triangle a zero normal
// (readers recompute it), three corners and a zero attribute word.
std::string write_stl(const TriangleMesh& m) {
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
