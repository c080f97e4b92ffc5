// Reading and writing whole files.  The only place dbss talks to the file
// system: the format and decoder libraries take and give bytes in memory.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "dbss/format/status.h"

namespace dbss::io {

// Reads a whole file into memory.  Fails with io naming the path (missing,
// unreadable, a directory, a device or socket) or limit_exceeded when it
// holds more than `max_size` bytes.  Pipes are read up to max_size.
Result<std::vector<uint8_t>> read_file(const std::string& path, uint64_t max_size = uint64_t{1} << 32);

// Writes `bytes` to a temporary file in the directory of `path`, flushes it
// to disk and renames it over `path`.  On any failure the temporary file is
// removed and `path` is left as it was; the Status names the path and the
// system's reason.
Status write_file_atomic(const std::string& path, std::span<const uint8_t> bytes);

}  // namespace dbss::io
