// Wavefront OBJ: vertices (`v`) and faces (`f`), read and written.
#include "formats.h"

#include <charconv>
#include <cstdio>

#include "text.h"

namespace dbss::io_detail {

Result<GeometryFile> parse_obj(const std::string& name, std::string_view text) {
  GeometryFile g;
  PointCloud& c = g.points;
  Lines lines(text);
  std::string_view line;
  std::vector<uint32_t> corners;
  while (lines.next(line)) {
    Tokens t(line);
    std::string_view tok;
    if (!t.next(tok)) continue;
    if (tok == "v") {
      double v[3];
      for (int k = 0; k < 3; ++k) {
        if (!t.next(tok) || !parse_double(tok, v[k]))
          return bad(name, at_line(lines.number()) + ": a 'v' line needs three numbers");
      }
      if (!push_point(c.xyz, v)) return bad(name, at_line(lines.number()) + ": coordinate is NaN, infinite or over 1e15");
    } else if (tok == "f") {
      // Corners are `v`, `v/vt`, `v//vn` or `v/vt/vn`; only v is used.  A
      // negative v counts back from the last vertex read so far.
      corners.clear();
      while (t.next(tok)) {
        const std::string_view v = tok.substr(0, tok.find('/'));
        long long i = 0;
        const auto r = std::from_chars(v.data(), v.data() + v.size(), i);
        if (r.ec != std::errc() || r.ptr != v.data() + v.size() || i == 0)
          return bad(name, at_line(lines.number()) + ": bad face corner '" + std::string(tok.substr(0, 40)) + "'");
        const long long n = static_cast<long long>(c.size());
        const long long index = i > 0 ? i - 1 : n + i;
        if (index < 0 || index >= n)
          return bad(name, at_line(lines.number()) + ": face corner " + std::to_string(i) + " names no vertex read so far (" +
                               std::to_string(n) + " vertices)");
        corners.push_back(static_cast<uint32_t>(index));
      }
      if (corners.size() < 3) return bad(name, at_line(lines.number()) + ": a face needs at least 3 corners");
      add_polygon(g.triangles, corners);
    }
  }
  return g;
}

Result<std::string> write_obj(const TriangleMesh& m) {
  std::string out = "# dbss\n";
  char b[96];
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    const int n = std::snprintf(b, sizeof b, "v %.9g %.9g %.9g\n", m.positions[3 * v], m.positions[3 * v + 1],
                                m.positions[3 * v + 2]);
    out.append(b, static_cast<size_t>(n));
  }
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    const int n = std::snprintf(b, sizeof b, "f %u %u %u\n", m.triangles[3 * f] + 1, m.triangles[3 * f + 1] + 1,
                                m.triangles[3 * f + 2] + 1);
    out.append(b, static_cast<size_t>(n));
  }
  return out;
}

}  // namespace dbss::io_detail
