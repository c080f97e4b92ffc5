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

// The commands' crease angle (`dbss encode`, `dbss compare`, the Python
// binding), degrees: creases on unless --crease-angle off or --no-creases.
// The library's CreaseOptions stays off by default.  On by default since
// the thirteenth session: measured (bench/crease_bench.md) smooth shapes,
// clean and noisy, get no tag and so the very file creases off writes,
// while machined parts get their feature lines.
inline constexpr double kCommandCreaseAngle = 30;

// `o` with the commands' defaults where the library's differ: as many
// levels as the points support, and creases on (kCommandCreaseAngle).
void set_command_defaults(EncodeOptions& o);

enum class OptionParse { not_mine, ok, bad };

// If args[i] is one of the reconstruction or coding options, consumes it and
// its value (advancing i) into `o`; on a bad value fills `error`.
OptionParse parse_encode_option(const std::vector<std::string_view>& args, size_t& i, EncodeOptions& o,
                                std::string& error);

}  // namespace dbss::tools
