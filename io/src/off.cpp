// OFF: vertices and faces (colours ignored), read and written.
#include "formats.h"

#include <cstdio>

#include "text.h"

namespace dbss::io_detail {

Result<GeometryFile> parse_off(const std::string& name, std::string_view text) {
  GeometryFile g;
  PointCloud& c = g.points;
  Lines lines(text);
  std::string_view line;
  // Numbers after the keyword, skipping comments and blank lines.
  std::vector<double> header_numbers;
  bool keyword = false;
  while (header_numbers.size() < 3 && lines.next(line)) {
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    Tokens t(line);
    std::string_view tok;
    while (t.next(tok)) {
      if (!keyword) {
        if (tok.size() < 3 || tok.substr(tok.size() - 3) != "OFF")
          return bad(name, at_line(lines.number()) + ": not an OFF file (no OFF keyword)");
        if (tok.find("4") != std::string_view::npos || tok.find("n") != std::string_view::npos)
          return bad(name, at_line(lines.number()) + ": only 3D OFF files are supported");
        keyword = true;
        continue;
      }
      double v;
      if (!parse_double(tok, v) || v < 0 || v != std::floor(v))
        return bad(name, at_line(lines.number()) + ": bad vertex/face/edge count '" + std::string(tok.substr(0, 40)) + "'");
      header_numbers.push_back(v);
    }
  }
  if (header_numbers.size() < 3) return bad(name, "OFF header is missing its vertex, face and edge counts");
  const double nv = header_numbers[0];
  // Each vertex line takes at least 6 bytes ("0 0 0\n").
  if (nv > static_cast<double>(text.size()) / 6) return bad(name, "OFF header declares more vertices than the file can hold");
  c.xyz.reserve(3 * static_cast<size_t>(nv));
  while (c.size() < static_cast<size_t>(nv)) {
    if (!lines.next(line))
      return bad(name, "file ends after " + std::to_string(c.size()) + " of " + std::to_string(size_t(nv)) + " vertices");
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    Tokens t(line);
    std::string_view tok;
    double v[3];
    int n = 0;
    while (n < 3 && t.next(tok)) {
      if (!parse_double(tok, v[n])) return bad(name, at_line(lines.number()) + ": '" + std::string(tok.substr(0, 40)) + "' is not a number");
      ++n;
    }
    if (n == 0) continue;
    if (n < 3) return bad(name, at_line(lines.number()) + ": a vertex needs three numbers");
    if (!push_point(c.xyz, v)) return bad(name, at_line(lines.number()) + ": coordinate is NaN, infinite or over 1e15");
  }
  // Faces: `n i_1 .. i_n` and optionally a colour after them.  A file cut
  // short in its faces keeps the faces read (a point reader never needed
  // them), but a malformed face is an error.
  const double nf = header_numbers[1];
  std::vector<uint32_t> corners;
  for (size_t f = 0; f < static_cast<size_t>(nf) && lines.next(line);) {
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    Tokens t(line);
    std::string_view tok;
    double n;
    if (!t.next(tok)) continue;
    if (!parse_double(tok, n) || n != std::floor(n) || n < 3 || n > 1e6)
      return bad(name, at_line(lines.number()) + ": face " + std::to_string(f) + " needs a corner count of at least 3");
    corners.clear();
    for (int k = 0; k < static_cast<int>(n); ++k) {
      double i;
      if (!t.next(tok) || !parse_double(tok, i) || i != std::floor(i))
        return bad(name, at_line(lines.number()) + ": face " + std::to_string(f) + " has a bad or missing corner");
      if (i < 0 || i >= static_cast<double>(c.size()))
        return bad(name, at_line(lines.number()) + ": face " + std::to_string(f) + " corner " + std::to_string(static_cast<long long>(i)) +
                             " is not a vertex (" + std::to_string(c.size()) + " vertices)");
      corners.push_back(static_cast<uint32_t>(i));
    }
    add_polygon(g.triangles, corners);
    ++f;
  }
  return g;
}

Result<std::string> write_off(const TriangleMesh& m) {
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
  return out;
}

}  // namespace dbss::io_detail
