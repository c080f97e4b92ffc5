// Command-line options shared by `dbss encode` and `dbss compare`.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "args.h"
#include "dbss/encoder/encode.h"

namespace dbss::tools {

// The option lines of the help text for the options parse_encode_option()
// takes.
extern const char* const kEncodeOptionsHelp;

enum class OptionParse { not_mine, ok, bad };

// If args[i] is one of the reconstruction or coding options, consumes it and
// its value (advancing i) into `o`; on a bad value fills `error`.
OptionParse parse_encode_option(const std::vector<std::string_view>& args, size_t& i, EncodeOptions& o,
                                std::string& error);

}  // namespace dbss::tools
