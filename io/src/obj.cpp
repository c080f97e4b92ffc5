// Wavefront OBJ: the `v` lines are read; faces are written.
#include "formats.h"

#include <cstdio>

#include "text.h"

namespace dbss::io_detail {

Result<PointCloud> parse_obj(const std::string& name, std::string_view text) {
  PointCloud c;
  Lines lines(text);
  std::string_view line;
  while (lines.next(line)) {
    Tokens t(line);
    std::string_view tok;
    if (!t.next(tok) || tok != "v") continue;
    double v[3];
    for (int k = 0; k < 3; ++k) {
      if (!t.next(tok) || !parse_double(tok, v[k]))
        return bad(name, at_line(lines.number()) + ": a 'v' line needs three numbers");
    }
    if (!push_point(c.xyz, v)) return bad(name, at_line(lines.number()) + ": coordinate is NaN, infinite or over 1e15");
  }
  return c;
}

std::string write_obj(const TriangleMesh& m) {
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
