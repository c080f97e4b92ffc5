#include "dbss/encoder/point_input.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>

#include "dbss/format/reader.h"

namespace dbss {

namespace {

Status bad(const std::string& name, const std::string& what) {
  return Status(ErrorCode::invalid_argument, name + ": " + what);
}

std::string lower_extension(const std::string& name) {
  const auto dot = name.find_last_of('.');
  const auto slash = name.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = name.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Splits text into lines, tracking the 1-based line number.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  size_t number() const { return number_; }
  size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  size_t pos_ = 0, number_ = 0;
};

// Whitespace-separated tokens of one line.
class Tokens {
 public:
  explicit Tokens(std::string_view s) : s_(s) {}
  bool next(std::string_view& tok) {
    while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\t')) ++p_;
    if (p_ >= s_.size()) return false;
    const size_t b = p_;
    while (p_ < s_.size() && s_[p_] != ' ' && s_[p_] != '\t') ++p_;
    tok = s_.substr(b, p_ - b);
    return true;
  }

 private:
  std::string_view s_;
  size_t p_ = 0;
};

bool parse_double(std::string_view tok, double& v) {
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  return r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

// Appends a point after checking it is finite and not over 1e15: squared
// distances of such coordinates would overflow binary32 in the KD-tree.
bool push_point(std::vector<float>& out, const double* v) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(v[k]) || std::abs(v[k]) > 1e15) return false;
  }
  for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(v[k]));
  return true;
}

std::string at_line(size_t n) { return "line " + std::to_string(n); }

// ---- XYZ -------------------------------------------------------------------

Result<PointCloud> parse_xyz(const std::string& name, std::string_view text) {
  PointCloud c;
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
  return c;
}

// ---- OBJ -------------------------------------------------------------------

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

// ---- OFF -------------------------------------------------------------------

Result<PointCloud> parse_off(const std::string& name, std::string_view text) {
  PointCloud c;
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
  return c;
}

// ---- STL -------------------------------------------------------------------

void merge_duplicates(std::vector<float>& xyz) {
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

}  // namespace

Result<PointCloud> parse_ply(const std::string& name, std::string_view bytes);  // ply_reader.cpp

Result<PointCloud> parse_points(const std::string& name, std::string_view bytes) {
  const std::string ext = lower_extension(name);
  Result<PointCloud> r = Status(ErrorCode::invalid_argument, "");
  if (ext == "xyz" || ext == "pts" || ext == "txt") {
    r = parse_xyz(name, bytes);
  } else if (ext == "obj") {
    r = parse_obj(name, bytes);
  } else if (ext == "off") {
    r = parse_off(name, bytes);
  } else if (ext == "stl") {
    r = parse_stl(name, bytes);
  } else if (ext == "ply") {
    r = parse_ply(name, bytes);
  } else {
    return bad(name, "unknown input format '." + ext + "' (expected .ply, .obj, .off, .xyz or .stl)");
  }
  if (r.ok() && r.value().size() == 0) return bad(name, "the file holds no points");
  return r;
}

Result<PointCloud> read_points(const std::string& path) {
  // The format first: a device or a file of another kind is refused before
  // anything is read.
  const std::string ext = lower_extension(path);
  if (ext != "xyz" && ext != "pts" && ext != "txt" && ext != "obj" && ext != "off" && ext != "stl" && ext != "ply")
    return bad(path, ext.empty() ? "no file extension to tell the format (expected .ply, .obj, .off, .xyz or .stl)"
                                 : "unknown input format '." + ext + "' (expected .ply, .obj, .off, .xyz or .stl)");
  // 4 GiB: over 100 million points in any of the formats, far beyond what
  // reconstruction handles on one machine.
  auto bytes = format::read_file(path, uint64_t{1} << 32);
  if (!bytes.ok()) return bytes.status();
  const std::vector<uint8_t>& b = bytes.value();
  return parse_points(path, std::string_view(reinterpret_cast<const char*>(b.data()), b.size()));
}

Status check_reconstructible(const PointCloud& c, const std::string& name) {
  const size_t n = c.size();
  if (n < 4) return bad(name, "needs at least 4 points, has " + std::to_string(n));
  auto p = [&](size_t i) { return std::array<double, 3>{c.xyz[3 * i], c.xyz[3 * i + 1], c.xyz[3 * i + 2]}; };
  auto sub = [](std::array<double, 3> a, std::array<double, 3> b) {
    return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  };
  auto dot = [](std::array<double, 3> a, std::array<double, 3> b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto cross = [](std::array<double, 3> a, std::array<double, 3> b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  // Farthest point from p0, farthest from the line, farthest from the plane:
  // the spread in each successive direction, relative to the extent.
  const auto p0 = p(0);
  size_t i1 = 0;
  double best = 0;
  for (size_t i = 1; i < n; ++i)
    if (double d = dot(sub(p(i), p0), sub(p(i), p0)); d > best) best = d, i1 = i;
  const double extent = std::sqrt(best);
  if (extent == 0) return bad(name, "all points are the same point");
  const auto axis = sub(p(i1), p0);
  size_t i2 = 0;
  best = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto cr = cross(axis, sub(p(i), p0));
    if (double d = dot(cr, cr); d > best) best = d, i2 = i;
  }
  if (std::sqrt(best) / dot(axis, axis) < 1e-6) return bad(name, "all points lie on one line");
  const auto normal = cross(axis, sub(p(i2), p0));
  const double nn = std::sqrt(dot(normal, normal));
  best = 0;
  for (size_t i = 0; i < n; ++i) best = std::max(best, std::abs(dot(normal, sub(p(i), p0))) / nn);
  if (best / extent < 1e-6) return bad(name, "all points lie on one plane; a closed surface needs volume");
  return {};
}

}  // namespace dbss
