#pragma once

#include <string_view>
#include <vector>

namespace dbss::tools {

// `dbss decode`: returns the process exit code.
int run_decode(const std::vector<std::string_view>& args);

}  // namespace dbss::tools
