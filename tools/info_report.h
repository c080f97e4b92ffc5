// What `dbss info` finds in a file's bytes, and its --json form.  Shared by
// the command (tools/info.cpp) and the Python module's dbss.info(), so both
// report the same fields from the same checks.  Uses format, decoder and io
// alone, like `dbss info` itself.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dbss/decoder/progressive.h"
#include "dbss/format/reader.h"

namespace dbss::tools {

struct InfoChunkRow {
  std::string type;
  uint64_t offset = 0, length = 0;
  bool verified = false;
};

struct InfoReport {
  ProgressiveDecoder decoder;        // holds the reader with every parsed chunk
  size_t file_bytes = 0;
  Status control;                    // the control mesh's check, as decode does it
  std::vector<uint64_t> level_hash;  // FNV-1a 64 per decoded level (only when asked for)
  bool valid = false;                // complete and the control mesh decodes
  Status first_error;
  std::vector<InfoChunkRow> rows;    // HEAD, INDX, then the table of contents
  std::vector<uint64_t> level_bytes; // compressed bytes per level (LEVL and its BDRY), from the table of contents
  std::vector<uint64_t> boundary_bytes; // of them, the level's BDRY chunk (format 1.3; 0 without one)
  const format::Reader& reader() const noexcept { return decoder.reader(); }
};

// Verifies `bytes` as `dbss info` does (every chunk, the control mesh) and,
// with `hashes`, decodes every verified level to hash it.
InfoReport inspect_bytes(std::span<const uint8_t> bytes, bool hashes, const format::Limits& limits = {});

// The `dbss info --json` object (ending in a newline); "file" is `path`, or
// null when there is none (bytes from memory).
std::string info_json(const InfoReport& report, const std::optional<std::string>& path);

}  // namespace dbss::tools
