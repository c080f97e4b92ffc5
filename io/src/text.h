// Shared pieces of the text readers: lines with their numbers, tokens,
// strict number parsing, and the coordinate checks every reader applies.
#pragma once

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "dbss/format/status.h"

namespace dbss::io_detail {

inline Status bad(const std::string& name, const std::string& what) {
  return Status(ErrorCode::invalid_argument, name + ": " + what);
}

inline std::string lower_extension(const std::string& name) {
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

inline bool parse_double(std::string_view tok, double& v) {
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  return r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

// Appends a point after checking it is finite and not over 1e15: squared
// distances of such coordinates would overflow binary32 in the KD-tree.
inline bool push_point(std::vector<float>& out, const double* v) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(v[k]) || std::abs(v[k]) > 1e15) return false;
  }
  for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(v[k]));
  return true;
}

inline std::string at_line(size_t n) { return "line " + std::to_string(n); }

// Appends polygon `corners` (0-based, already checked against the vertex
// count) as a fan of triangles from its first corner.
inline void add_polygon(std::vector<uint32_t>& triangles, const std::vector<uint32_t>& corners) {
  for (size_t k = 2; k < corners.size(); ++k) {
    triangles.push_back(corners[0]);
    triangles.push_back(corners[k - 1]);
    triangles.push_back(corners[k]);
  }
}

}  // namespace dbss::io_detail
