#pragma once

#include <string_view>
#include <vector>

namespace dbss::tools {

// `dbss compare`: returns the process exit code.
int run_compare(const std::vector<std::string_view>& args);

}  // namespace dbss::tools
