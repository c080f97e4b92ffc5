// PLY vertices: ascii and binary in either byte order, any numeric type.
// Our own reader rather than Draco's, which reads neither big-endian files
// nor reports where a file is broken.
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "formats.h"
#include "text.h"

namespace dbss::io_detail {

namespace {

enum class Type { i8, u8, i16, u16, i32, u32, f32, f64, none };

Type type_of(std::string_view s) {
  if (s == "char" || s == "int8") return Type::i8;
  if (s == "uchar" || s == "uint8") return Type::u8;
  if (s == "short" || s == "int16") return Type::i16;
  if (s == "ushort" || s == "uint16") return Type::u16;
  if (s == "int" || s == "int32") return Type::i32;
  if (s == "uint" || s == "uint32") return Type::u32;
  if (s == "float" || s == "float32") return Type::f32;
  if (s == "double" || s == "float64") return Type::f64;
  return Type::none;
}

size_t size_of(Type t) {
  switch (t) {
    case Type::i8: case Type::u8: return 1;
    case Type::i16: case Type::u16: return 2;
    case Type::i32: case Type::u32: case Type::f32: return 4;
    case Type::f64: return 8;
    case Type::none: return 0;
  }
  return 0;
}

struct Property {
  std::string name;
  Type type = Type::none;
  Type count_type = Type::none;  // list properties only
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

double load(const unsigned char* p, Type t, bool swap) {
  unsigned char b[8];
  const size_t n = size_of(t);
  for (size_t i = 0; i < n; ++i) b[i] = swap ? p[n - 1 - i] : p[i];
  switch (t) {
    case Type::i8: { int8_t v; std::memcpy(&v, b, 1); return v; }
    case Type::u8: return b[0];
    case Type::i16: { int16_t v; std::memcpy(&v, b, 2); return v; }
    case Type::u16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
    case Type::i32: { int32_t v; std::memcpy(&v, b, 4); return v; }
    case Type::u32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
    case Type::f32: { float v; std::memcpy(&v, b, 4); return v; }
    case Type::f64: { double v; std::memcpy(&v, b, 8); return v; }
    case Type::none: return 0;
  }
  return 0;
}

}  // namespace

Result<GeometryFile> parse_ply(const std::string& name, std::string_view bytes) {
  // Header.
  size_t pos = 0, line_no = 0;
  auto next_line = [&](std::string_view& line) {
    if (pos >= bytes.size()) return false;
    size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) return false;
    line = bytes.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    ++line_no;
    return true;
  };
  std::string_view line;
  if (!next_line(line) || line != "ply") return bad(name, "not a PLY file (first line is not 'ply')");
  enum { ascii, little, big } fmt = ascii;
  bool have_format = false;
  std::vector<Element> elements;
  for (;;) {
    if (!next_line(line)) return bad(name, "PLY header has no 'end_header'");
    if (line == "end_header") break;
    std::vector<std::string_view> w;
    for (size_t i = 0; i < line.size();) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      if (j > i) w.push_back(line.substr(i, j - i));
      i = j;
    }
    const std::string where = "line " + std::to_string(line_no);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (w.size() < 2) return bad(name, where + ": bad format line");
      if (w[1] == "ascii") fmt = ascii;
      else if (w[1] == "binary_little_endian") fmt = little;
      else if (w[1] == "binary_big_endian") fmt = big;
      else return bad(name, where + ": unknown PLY format '" + std::string(w[1]) + "'");
      have_format = true;
    } else if (w[0] == "element") {
      uint64_t n = 0;
      if (w.size() != 3 || std::from_chars(w[2].data(), w[2].data() + w[2].size(), n).ec != std::errc())
        return bad(name, where + ": bad element line");
      elements.push_back({std::string(w[1]), n, {}});
    } else if (w[0] == "property") {
      if (elements.empty()) return bad(name, where + ": property before any element");
      Property p;
      if (w.size() == 5 && w[1] == "list") {
        p.count_type = type_of(w[2]);
        p.type = type_of(w[3]);
        p.name = w[4];
        if (p.count_type == Type::none || p.type == Type::none || p.count_type == Type::f32 || p.count_type == Type::f64)
          return bad(name, where + ": bad list property types");
      } else if (w.size() == 3) {
        p.type = type_of(w[1]);
        p.name = w[2];
        if (p.type == Type::none) return bad(name, where + ": unknown property type '" + std::string(w[1]) + "'");
      } else {
        return bad(name, where + ": bad property line");
      }
      elements.back().props.push_back(p);
    } else {
      return bad(name, where + ": unexpected header line");
    }
  }
  if (!have_format) return bad(name, "PLY header has no format line");

  GeometryFile g;
  PointCloud& c = g.points;
  bool found = false;
  std::vector<double> face_corners;   // every face's corners in order
  std::vector<size_t> face_offsets{0};
  const bool swap = (fmt == big) != (std::endian::native == std::endian::big);
  for (const Element& e : elements) {
    int ix[6] = {-1, -1, -1, -1, -1, -1};
    const bool vertex = e.name == "vertex" && !found;
    static const char* kNames[6] = {"x", "y", "z", "nx", "ny", "nz"};
    if (vertex) {
      for (size_t i = 0; i < e.props.size(); ++i)
        for (int k = 0; k < 6; ++k)
          if (e.props[i].name == kNames[k] && e.props[i].count_type == Type::none) ix[k] = static_cast<int>(i);
      if (ix[0] < 0 || ix[1] < 0 || ix[2] < 0) return bad(name, "vertex element has no x, y and z properties");
      found = true;
      // Each vertex takes at least one byte per property (or two chars in ascii).
      if (e.count > (bytes.size() - pos) / std::max<size_t>(1, e.props.size()))
        return bad(name, "vertex count " + std::to_string(e.count) + " is more than the file can hold");
      c.xyz.reserve(3 * e.count);
    }
    const bool want_normals = vertex && ix[3] >= 0 && ix[4] >= 0 && ix[5] >= 0;
    // The faces: the first list named vertex_indices (or vertex_index) of
    // the face element; other lists are skipped.
    int face_list = -1;
    if (e.name == "face")
      for (size_t i = 0; i < e.props.size() && face_list < 0; ++i)
        if (e.props[i].count_type != Type::none && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index"))
          face_list = static_cast<int>(i);
    // Corners are checked once every element is read: the face element
    // may come before the vertex element.
    auto add_corner = [&](double v, uint64_t) { face_corners.push_back(v); };
    std::vector<double> row(e.props.size());
    for (uint64_t r = 0; r < e.count; ++r) {
      if (fmt == ascii) {
        std::string_view l;
        do {
          if (!next_line(l)) {
            // The last line may lack its newline.
            if (pos < bytes.size()) {
              l = bytes.substr(pos);
              pos = bytes.size();
              ++line_no;
            } else {
              return bad(name, "file ends in element '" + e.name + "' at row " + std::to_string(r) + " of " + std::to_string(e.count));
            }
          }
        } while (l.find_first_not_of(" \t") == std::string_view::npos);
        size_t i = 0;
        auto token = [&](double& v) {
          while (i < l.size() && (l[i] == ' ' || l[i] == '\t')) ++i;
          size_t j = i;
          while (j < l.size() && l[j] != ' ' && l[j] != '\t') ++j;
          if (j == i) return false;
          const char* b = l.data() + i;
          if (*b == '+') ++b;
          const auto res = std::from_chars(b, l.data() + j, v);
          i = j;
          return res.ec == std::errc() && res.ptr == l.data() + j;
        };
        for (size_t p = 0; p < e.props.size(); ++p) {
          double v;
          if (!token(v)) return bad(name, "line " + std::to_string(line_no) + ": bad or missing value for '" + e.props[p].name + "'");
          if (e.props[p].count_type != Type::none) {
            if (v < 0 || v > 1e6 || v != std::floor(v)) return bad(name, "line " + std::to_string(line_no) + ": bad list length");
            for (uint64_t k = 0; k < static_cast<uint64_t>(v); ++k) {
              double item;
              if (!token(item)) return bad(name, "line " + std::to_string(line_no) + ": list '" + e.props[p].name + "' cut short");
              if (static_cast<int>(p) == face_list) add_corner(item, r);
            }
          }
          row[p] = v;
        }
      } else {
        for (size_t p = 0; p < e.props.size(); ++p) {
          const Property& pr = e.props[p];
          const size_t start = pos;
          if (pr.count_type != Type::none) {
            if (bytes.size() - pos < size_of(pr.count_type))
              return bad(name, "byte " + std::to_string(start) + ": file ends in element '" + e.name + "'");
            const double n = load(reinterpret_cast<const unsigned char*>(bytes.data() + pos), pr.count_type, swap);
            pos += size_of(pr.count_type);
            if (n < 0 || n * size_of(pr.type) > static_cast<double>(bytes.size() - pos))
              return bad(name, "byte " + std::to_string(start) + ": list '" + pr.name + "' runs past the end of the file");
            if (static_cast<int>(p) == face_list) {
              for (size_t k = 0; k < static_cast<size_t>(n); ++k)
                add_corner(load(reinterpret_cast<const unsigned char*>(bytes.data() + pos + k * size_of(pr.type)), pr.type, swap), r);
            }
            pos += static_cast<size_t>(n) * size_of(pr.type);
            row[p] = n;
          } else {
            if (bytes.size() - pos < size_of(pr.type))
              return bad(name, "byte " + std::to_string(start) + ": file ends in element '" + e.name + "' at row " +
                                   std::to_string(r) + " of " + std::to_string(e.count));
            row[p] = load(reinterpret_cast<const unsigned char*>(bytes.data() + pos), pr.type, swap);
            pos += size_of(pr.type);
          }
        }
      }
      if (face_list >= 0) {
        if (face_corners.size() - face_offsets.back() < 3) return bad(name, "face " + std::to_string(r) + " has fewer than 3 corners");
        face_offsets.push_back(face_corners.size());
      }
      if (vertex) {
        const double v[3] = {row[ix[0]], row[ix[1]], row[ix[2]]};
        for (double x : v)
          if (!std::isfinite(x) || std::abs(x) > 1e15)
            return bad(name, (fmt == ascii ? "line " + std::to_string(line_no) : "vertex " + std::to_string(r)) +
                                 ": coordinate is NaN, infinite or over 1e15");
        for (double x : v) c.xyz.push_back(static_cast<float>(x));
        if (want_normals)
          for (int k = 3; k < 6; ++k) c.normals.push_back(static_cast<float>(row[ix[k]]));
      }
    }
  }
  if (!found) return bad(name, "PLY file has no vertex element");
  std::vector<uint32_t> corners;
  for (size_t f = 0; f + 1 < face_offsets.size(); ++f) {
    corners.clear();
    for (size_t k = face_offsets[f]; k < face_offsets[f + 1]; ++k) {
      const double v = face_corners[k];
      if (!(v >= 0 && v < static_cast<double>(c.size()) && v == std::floor(v)))
        return bad(name, "face " + std::to_string(f) + " has corner " + std::to_string(static_cast<long long>(v)) +
                             ", not a vertex (" + std::to_string(c.size()) + " vertices)");
      corners.push_back(static_cast<uint32_t>(v));
    }
    add_polygon(g.triangles, corners);
  }
  return g;
}

// Binary little-endian: the smallest and fastest to read back.
Result<std::string> write_ply(const TriangleMesh& m) {
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment dbss\nelement vertex " + std::to_string(m.vertex_count()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(m.triangle_count()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  auto u32 = [&](uint32_t u) {
    const char le[4] = {char(u), char(u >> 8), char(u >> 16), char(u >> 24)};
    out.append(le, 4);
  };
  for (float x : m.positions) u32(std::bit_cast<uint32_t>(x));
  for (size_t f = 0; f < m.triangle_count(); ++f) {
    out.push_back(3);
    for (int k = 0; k < 3; ++k) u32(m.triangles[3 * f + k]);
  }
  return out;
}

}  // namespace dbss::io_detail
