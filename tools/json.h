// JSON string quoting for the commands' --json output.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace dbss::tools {

// `s` as a JSON string literal; bytes outside printable ASCII become \u00XX,
// so any file name or metadata value prints as valid JSON.
inline std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (unsigned char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += static_cast<char>(ch);
    } else if (ch < 0x20 || ch >= 0x7F) {
      char b[8];
      std::snprintf(b, sizeof b, "\\u%04x", ch);
      out += b;
    } else {
      out += static_cast<char>(ch);
    }
  }
  return out + "\"";
}

}  // namespace dbss::tools
