// Parsing option values for every dbss command.
#pragma once

#include <string_view>

namespace dbss::tools {

// Whole number in [lo, hi], nothing else in `s`.
bool parse_int(std::string_view s, long lo, long hi, long& out);

// A number as strtod reads it, nothing else in `s`.
bool parse_double(std::string_view s, double& out);

}  // namespace dbss::tools
