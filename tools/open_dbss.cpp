#include "open_dbss.h"

#include <cstdio>

#include "dbss/io/file.h"

namespace dbss::tools {

bool open_dbss(const char* command, const std::string& input, ProgressiveDecoder& d, Status& end) {
  auto bytes = io::read_file(input);
  if (!bytes.ok()) {
    std::fprintf(stderr, "dbss %s: %s\n", command, bytes.status().message().c_str());
    return false;
  }
  d.feed(bytes.value());
  end = d.finish();
  if (d.ready_level() < 0) {
    std::fprintf(stderr, "dbss %s: %s: %s\n", command, input.c_str(), end.to_string().c_str());
    return false;
  }
  return true;
}

}  // namespace dbss::tools
