#pragma once

#include <string_view>
#include <vector>

namespace dbss::tools {

// `dbss info`: returns the process exit code.
int run_info(const std::vector<std::string_view>& args);

}  // namespace dbss::tools
