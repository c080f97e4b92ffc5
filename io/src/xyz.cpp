// XYZ: one point per line, `x y z` or `x y z nx ny nz`; # and // comments.
#include "formats.h"
#include "text.h"

namespace dbss::io_detail {

Result<GeometryFile> parse_xyz(const std::string& name, std::string_view text) {
  GeometryFile g;
  PointCloud& c = g.points;
  Lines lines(text);
  std::string_view line;
  bool normals = true;
  while (lines.next(line)) {
    Tokens t(line);
    std::string_view tok;
    double v[6];
    int n = 0;
    bool comment = false;
    while (t.next(tok)) {
      if (n == 0 && (tok[0] == '#' || tok.substr(0, 2) == "//")) {
        comment = true;
        break;
      }
      if (n < 6 && !parse_double(tok, v[n]))
        return bad(name, at_line(lines.number()) + ": '" + std::string(tok.substr(0, 40)) + "' is not a number");
      ++n;
    }
    if (comment || n == 0) continue;
    if (n < 3) return bad(name, at_line(lines.number()) + ": expected x y z, found " + std::to_string(n) + " values");
    if (!push_point(c.xyz, v)) return bad(name, at_line(lines.number()) + ": coordinate is NaN, infinite or over 1e15");
    if (n >= 6 && normals) {
      for (int k = 3; k < 6; ++k) c.normals.push_back(static_cast<float>(v[k]));
    } else {
      normals = false;
    }
  }
  if (!normals || c.normals.size() != c.xyz.size()) c.normals.clear();
  return g;
}

}  // namespace dbss::io_detail
