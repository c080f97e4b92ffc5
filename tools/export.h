#pragma once

#include <string_view>
#include <vector>

namespace dbss::tools {

// `dbss export`: returns the process exit code.
int run_export(const std::vector<std::string_view>& args);

}  // namespace dbss::tools
