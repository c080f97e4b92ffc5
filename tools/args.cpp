#include "args.h"

#include <charconv>
#include <cstdlib>
#include <string>

namespace dbss::tools {

bool parse_int(std::string_view s, long lo, long hi, long& out) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && out >= lo && out <= hi;
}

bool parse_double(std::string_view s, double& out) {
  const std::string text(s);
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

}  // namespace dbss::tools
