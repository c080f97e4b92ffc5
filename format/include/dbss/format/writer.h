// Writing .dbss containers.
//
// serialize() builds a whole file in memory; dbss::io::write_file_atomic()
// (dbss/io/file.h) puts bytes under a path without ever leaving a partial
// file under that name.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "dbss/format/container.h"
#include "dbss/format/status.h"

namespace dbss::format {

struct FileContents {
  // level_count and the control counts must agree with `levels`; the writer
  // checks, it does not fill them in.
  Header header;
  ControlCodec control_codec = ControlCodec::draco;
  std::vector<uint8_t> control_mesh;  // the codec's bytes, not empty
  std::vector<Level> levels;          // levels[i].index == i + 1
  // Optional: empty, or levels[i]'s LEVL chunk data as encode_level made it
  // (an encoder that compressed each level to choose its coding keeps those
  // bytes, and serialize() writes them instead of compressing again).
  std::vector<std::vector<uint8_t>> level_data;
  // Optional, the same for BDRY chunks: empty, or per level its BDRY chunk
  // data as encode_boundary made it (empty for a level without boundary
  // values).
  std::vector<std::vector<uint8_t>> boundary_data;
  std::vector<MetaEntry> metadata;    // one 'meta' chunk after the last level when not empty
  // Crease tags: empty, or a CREA chunk right after CTRL; then
  // header.version_minor must be kCreaseVersionMinor or more.
  Creases creases;
};

struct WriteOptions {
  int zstd_level = 19;  // ZSTD_minCLevel()..ZSTD_maxCLevel()
};

// One chunk after INDX, with its data; used for any chunk type.
struct RawChunk {
  ChunkType type;
  std::vector<uint8_t> data;
};

// The data bytes of a HEAD chunk (kHeadSize bytes, little-endian).
std::vector<uint8_t> encode_header(const Header& header);

// The data bytes of a LEVL chunk: `level` checked (finite positive step,
// |q| <= kMaxAbsDisplacement) and zstd-compressed at `zstd_level`.
Result<std::vector<uint8_t>> encode_level(const Level& level, int zstd_level);

// The data bytes of the BDRY chunk of `level` (version 1.3): its boundary
// values, laid out as a LEVL with boundary.q for q.  Fails as encode_level.
Result<std::vector<uint8_t>> encode_boundary(const Level& level, int zstd_level);
// The data bytes of a CTRL chunk.
std::vector<uint8_t> encode_control(ControlCodec codec, std::span<const uint8_t> payload);

// The data bytes of a CREA chunk for a control mesh of `edges` edges and
// `vertices` vertices; fails if the sizes differ or no bit is set.
Result<std::vector<uint8_t>> encode_creases(const Creases& creases, uint32_t edges, uint32_t vertices);
// The data bytes of a 'meta' chunk; fails on an empty or over-long key.
Result<std::vector<uint8_t>> encode_metadata(const std::vector<MetaEntry>& entries);

// Signature, HEAD, an INDX listing `body`, then `body` in order, each chunk
// framed with its length and CRC32C.  Performs no semantic checks, so tests
// can build any file, valid or not.
std::vector<uint8_t> assemble(std::span<const uint8_t> head_data, std::span<const RawChunk> body);

// The lowest minor version that can hold `contents`: 0, 1 with crease
// tags, 2 with a level coded DisplacementCoding::context, 3 with a level
// that has boundary values (a BDRY chunk).  Writers that
// want the widest readership set header.version_minor to this.
uint16_t minimum_version_minor(const FileContents& contents);

// A complete, valid file: checks `contents` against the format's rules
// (including that each level has the odd-vertex count the control counts
// imply) and returns invalid_argument naming the first problem.
Result<std::vector<uint8_t>> serialize(const FileContents& contents, const WriteOptions& options = {});

// A file and the table of contents its INDX chunk lists (the chunks after
// INDX, in file order: what Reader::toc() reads back).
struct SerializedFile {
  std::vector<uint8_t> bytes;
  std::vector<TocEntry> toc;
};

// serialize(), also returning the table of contents it wrote.
Result<SerializedFile> serialize_with_toc(const FileContents& contents, const WriteOptions& options = {});

}  // namespace dbss::format
