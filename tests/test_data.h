// The real scans under test-data/ (Debian's libcgal-demo data, unpacked by
// scripts/fetch-test-data.sh; not committed).  A test asks for a file by
// its path inside the data set and returns when it gets nothing:
//
//   const auto path = test::scan_data("data/meshes/bunny00.off");
//   if (!path) return;
//
// A missing file skips the test with a warning, for developers offline;
// under CI=true it fails the test instead, so CI cannot go green without
// ever running a real scan.
#pragma once

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace dbss::test {

// True when the environment variable CI is "true" (as CI services set it).
inline bool running_in_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string_view(ci) == "true";
}

// The absolute path of test-data/<relative>, or nothing (after a warning)
// when it is absent; absent under CI=true, the current test fails here.
inline std::optional<std::string> scan_data(const std::string& relative) {
  std::string path = std::string(DBSS_SOURCE_DIR) + "/test-data/" + relative;
  if (std::filesystem::is_regular_file(path)) return path;
  if (running_in_ci())
    FAIL("missing test data " << path << " with CI=true: run scripts/fetch-test-data.sh (needs the Debian archive); "
                              << "offline, run the tests without CI=true to skip the scan tests");
  WARN("skipped: run scripts/fetch-test-data.sh for " << path);
  return std::nullopt;
}

}  // namespace dbss::test
