#pragma once

#include <string_view>
#include <vector>

namespace dbss::tools {

// `dbss encode`: returns the process exit code.
int run_encode(const std::vector<std::string_view>& args);

}  // namespace dbss::tools
