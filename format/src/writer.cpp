#include "dbss/format/writer.h"

#include <zstd.h>

#include <algorithm>
#include <cmath>

#include "byte_io.h"
#include "context_coding.h"
#include "dbss/format/crc32c.h"
#include "rules.h"

namespace dbss::format {

using namespace detail;

namespace {

// The fields a LEVL chunk's data begins with, before the payload's size.
void put_level_fields(std::vector<uint8_t>& d, const Level& level) {
  put_u8(d, level.index);
  put_u8(d, static_cast<uint8_t>(level.coding));
  put_u16(d, 0);
  put_u32(d, static_cast<uint32_t>(level.q.size()));
  put_f32(d, level.step);
}

}  // namespace

std::vector<uint8_t> encode_header(const Header& h) {
  std::vector<uint8_t> d;
  d.reserve(kHeadSize);
  put_u16(d, h.version_major);
  put_u16(d, h.version_minor);
  put_u32(d, h.flags);
  put_u8(d, h.level_count);
  put_u8(d, h.displacement_mode);
  put_u8(d, h.control_position_bits);
  put_u8(d, 0);
  put_u32(d, h.control_vertex_count);
  put_u32(d, h.control_edge_count);
  put_u32(d, h.control_triangle_count);
  for (float v : h.bbox_min) put_f32(d, v);
  for (float v : h.bbox_max) put_f32(d, v);
  put_f32(d, h.error_target);
  put_u32(d, 0);
  return d;
}

Result<std::vector<uint8_t>> encode_level(const Level& level, int zstd_level) {
  auto bad = [&](const std::string& what) {
    return Status(ErrorCode::invalid_argument, "level " + std::to_string(level.index) + ": " + what);
  };
  if (level.coding != DisplacementCoding::byte_planes && level.coding != DisplacementCoding::varint &&
      level.coding != DisplacementCoding::context)
    return bad("unknown displacement coding");
  if (!std::isfinite(level.step) || !(level.step > 0)) return bad("step must be finite and positive");
  if (level.q.size() > 0xFFFFFFFFu) return bad("too many displacements");
  for (size_t i = 0; i < level.q.size(); ++i)
    if (level.q[i] > kMaxAbsDisplacement || level.q[i] < -kMaxAbsDisplacement)
      return bad("displacement #" + std::to_string(i) + " = " + std::to_string(level.q[i]) + " is outside -2^24..2^24");

  if (level.coding == DisplacementCoding::context) {
    // No zstd: raw_size is the coded stream's own size (spec section 9b).
    const std::vector<uint8_t> stream = context_encode(level.q);
    std::vector<uint8_t> d;
    put_level_fields(d, level);
    put_u32(d, static_cast<uint32_t>(stream.size()));
    put_bytes(d, stream.data(), stream.size());
    return d;
  }
  const std::vector<uint8_t> raw = pack_displacements(level.q, level.coding);
  std::vector<uint8_t> d;
  put_level_fields(d, level);
  put_u32(d, static_cast<uint32_t>(raw.size()));
  const size_t head = d.size();
  d.resize(head + ZSTD_compressBound(raw.size()));
  const size_t n = ZSTD_compress(d.data() + head, d.size() - head, raw.data(), raw.size(), zstd_level);
  if (ZSTD_isError(n)) return bad(std::string("zstd: ") + ZSTD_getErrorName(n));
  d.resize(head + n);
  return d;
}

Result<std::vector<uint8_t>> encode_boundary(const Level& level, int zstd_level) {
  // Section 9c: the same fields and payload as a LEVL, with the boundary
  // values for the displacements.
  Level as_level;
  as_level.index = level.index;
  as_level.coding = level.boundary.coding;
  as_level.step = level.boundary.step;
  as_level.q = level.boundary.q;
  auto d = encode_level(as_level, zstd_level);
  if (!d.ok()) return Status(ErrorCode::invalid_argument, "boundary values of " + d.status().message());
  return d;
}

std::vector<uint8_t> encode_control(ControlCodec codec, std::span<const uint8_t> payload) {
  std::vector<uint8_t> d;
  d.reserve(4 + payload.size());
  put_u8(d, static_cast<uint8_t>(codec));
  put_u8(d, 0);
  put_u16(d, 0);
  put_bytes(d, payload.data(), payload.size());
  return d;
}

Result<std::vector<uint8_t>> encode_metadata(const std::vector<MetaEntry>& entries) {
  std::vector<uint8_t> d;
  put_u32(d, static_cast<uint32_t>(entries.size()));
  for (const MetaEntry& e : entries) {
    if (!meta_key_valid(e.key))
      return Status(ErrorCode::invalid_argument, "metadata key '" + e.key + "' must be 1..255 bytes of UTF-8 without NUL");
    if (e.value.size() > 0xFFFFFFFFu) return Status(ErrorCode::invalid_argument, "metadata value too long");
    put_u8(d, static_cast<uint8_t>(e.key.size()));
    put_bytes(d, e.key.data(), e.key.size());
    put_u32(d, static_cast<uint32_t>(e.value.size()));
    put_bytes(d, e.value.data(), e.value.size());
  }
  return d;
}

namespace {

void put_chunk(std::vector<uint8_t>& out, ChunkType type, std::span<const uint8_t> data) {
  const size_t start = out.size();
  put_u32(out, static_cast<uint32_t>(data.size()));
  put_bytes(out, type.c.data(), 4);
  put_bytes(out, data.data(), data.size());
  const uint32_t crc = crc32c(std::span<const uint8_t>(out.data() + start, out.size() - start));
  put_u32(out, crc);
}

// assemble(), also listing the table of contents in `listed` when not null.
std::vector<uint8_t> assemble_file(std::span<const uint8_t> head_data, std::span<const RawChunk> body,
                                   std::vector<TocEntry>* listed) {
  const uint64_t toc_data = 16 + 16 * uint64_t{body.size()};
  const uint64_t body_start = kSignature.size() + kChunkOverhead + head_data.size() + kChunkOverhead + toc_data;
  uint64_t end = body_start;
  std::vector<uint8_t> toc;
  toc.reserve(toc_data);
  for (const RawChunk& c : body) end += kChunkOverhead + c.data.size();
  put_u64(toc, end);
  put_u32(toc, static_cast<uint32_t>(body.size()));
  put_u32(toc, 0);
  uint64_t at = body_start;
  for (const RawChunk& c : body) {
    put_bytes(toc, c.type.c.data(), 4);
    put_u32(toc, static_cast<uint32_t>(c.data.size()));
    put_u64(toc, at);
    if (listed) listed->push_back({c.type, static_cast<uint32_t>(c.data.size()), at});
    at += kChunkOverhead + c.data.size();
  }

  std::vector<uint8_t> out;
  out.reserve(end);
  put_bytes(out, kSignature.data(), kSignature.size());
  put_chunk(out, kHead, head_data);
  put_chunk(out, kIndx, toc);
  for (const RawChunk& c : body) put_chunk(out, c.type, c.data);
  return out;
}

}  // namespace

Result<std::vector<uint8_t>> encode_creases(const Creases& creases, uint32_t edges, uint32_t vertices) {
  return detail::encode_creases(creases, edges, vertices);
}

std::vector<uint8_t> assemble(std::span<const uint8_t> head_data, std::span<const RawChunk> body) {
  return assemble_file(head_data, body, nullptr);
}

uint16_t minimum_version_minor(const FileContents& c) {
  for (const Level& level : c.levels)
    if (!level.boundary.empty()) return kBoundaryVersionMinor;
  for (const Level& level : c.levels)
    if (level.coding == DisplacementCoding::context) return kContextCodingVersionMinor;
  return c.creases.empty() ? 0 : kCreaseVersionMinor;
}

Result<std::vector<uint8_t>> serialize(const FileContents& c, const WriteOptions& options) {
  auto file = serialize_with_toc(c, options);
  if (!file.ok()) return file.status();
  return std::move(file.value().bytes);
}

Result<SerializedFile> serialize_with_toc(const FileContents& c, const WriteOptions& options) {
  auto bad = [](const std::string& what) { return Status(ErrorCode::invalid_argument, what); };
  if (Status s = check_header(c.header, Status::kNoOffset); !s.ok())
    return Status(ErrorCode::invalid_argument, s.message());
  if (c.header.level_count != c.levels.size())
    return bad("header says " + std::to_string(c.header.level_count) + " levels but " +
               std::to_string(c.levels.size()) + " are given");
  if (c.control_codec != ControlCodec::draco) return bad("unknown control mesh codec");
  if (c.control_mesh.empty()) return bad("control mesh bytes are empty");
  if (options.zstd_level < ZSTD_minCLevel() || options.zstd_level > ZSTD_maxCLevel())
    return bad("zstd level " + std::to_string(options.zstd_level) + " out of range");
  std::vector<uint64_t> odd;
  if (Status s = derived_odd_counts(c.header, Status::kNoOffset, odd); !s.ok())
    return Status(ErrorCode::invalid_argument, s.message());

  if (!c.level_data.empty() && c.level_data.size() != c.levels.size())
    return bad(std::to_string(c.level_data.size()) + " levels' chunk data for " + std::to_string(c.levels.size()) +
               " levels");
  if (!c.boundary_data.empty() && c.boundary_data.size() != c.levels.size())
    return bad(std::to_string(c.boundary_data.size()) + " levels' boundary chunk data for " +
               std::to_string(c.levels.size()) + " levels");

  std::vector<RawChunk> body;
  body.push_back({kCtrl, encode_control(c.control_codec, c.control_mesh)});
  if (!c.creases.empty()) {
    if (c.header.version_minor < kCreaseVersionMinor)
      return bad("crease tags need version 1." + std::to_string(kCreaseVersionMinor) + ", the header says 1." +
                 std::to_string(c.header.version_minor));
    auto data = detail::encode_creases(c.creases, c.header.control_edge_count, c.header.control_vertex_count);
    if (!data.ok()) return data.status();
    body.push_back({kCrea, std::move(data).value()});
  }
  for (size_t i = 0; i < c.levels.size(); ++i) {
    const Level& level = c.levels[i];
    if (level.index != i + 1) return bad("levels[" + std::to_string(i) + "] has index " + std::to_string(level.index));
    if (level.coding == DisplacementCoding::context && c.header.version_minor < kContextCodingVersionMinor)
      return bad("level " + std::to_string(i + 1) + "'s context coding needs version 1." +
                 std::to_string(kContextCodingVersionMinor) + ", the header says 1." +
                 std::to_string(c.header.version_minor));
    if (level.q.size() != odd[i])
      return bad("level " + std::to_string(i + 1) + " has " + std::to_string(level.q.size()) +
                 " displacements; its odd-vertex count is " + std::to_string(odd[i]));
    if (!level.boundary.empty()) {
      // Section 9c: right before its LEVL, one value per boundary edge.
      if (c.header.version_minor < kBoundaryVersionMinor)
        return bad("level " + std::to_string(i + 1) + "'s boundary values need version 1." +
                   std::to_string(kBoundaryVersionMinor) + ", the header says 1." +
                   std::to_string(c.header.version_minor));
      const MeshCounts control{c.header.control_vertex_count, c.header.control_edge_count,
                               c.header.control_triangle_count};
      const auto boundary = boundary_edge_count(control, static_cast<uint32_t>(i));
      if (!boundary || level.boundary.q.size() != *boundary)
        return bad("level " + std::to_string(i + 1) + " has " + std::to_string(level.boundary.q.size()) +
                   " boundary values; the level before has " + std::to_string(boundary.value_or(0)) +
                   " boundary edges");
      if (!c.boundary_data.empty() && !c.boundary_data[i].empty()) {
        // Made by encode_boundary, which checked the values: only that
        // the data is this level's (its fields) is checked here.
        const std::vector<uint8_t>& data = c.boundary_data[i];
        Level as_level;
        as_level.index = level.index;
        as_level.coding = level.boundary.coding;
        as_level.step = level.boundary.step;
        as_level.q.resize(level.boundary.q.size());  // (only its count is written)
        std::vector<uint8_t> fields;
        put_level_fields(fields, as_level);
        if (data.size() < fields.size() + 4 || !std::equal(fields.begin(), fields.end(), data.begin()))
          return bad("the boundary chunk data given for level " + std::to_string(i + 1) + " is not that level's");
        body.push_back({kBdry, data});
      } else {
        auto data = encode_boundary(level, options.zstd_level);
        if (!data.ok()) return data.status();
        body.push_back({kBdry, std::move(data).value()});
      }
    }
    if (!c.level_data.empty()) {
      // Made by encode_level, which checked the level: only that the data
      // is this level's is checked here.
      const std::vector<uint8_t>& data = c.level_data[i];
      std::vector<uint8_t> fields;
      put_level_fields(fields, level);
      if (data.size() < fields.size() + 4 || !std::equal(fields.begin(), fields.end(), data.begin()))
        return bad("the chunk data given for level " + std::to_string(i + 1) + " is not that level's");
      body.push_back({kLevl, data});
      continue;
    }
    auto data = encode_level(level, options.zstd_level);
    if (!data.ok()) return data.status();
    body.push_back({kLevl, std::move(data).value()});
  }
  if (!c.metadata.empty()) {
    auto data = encode_metadata(c.metadata);
    if (!data.ok()) return data.status();
    body.push_back({kMeta, std::move(data).value()});
  }
  for (const RawChunk& r : body)
    if (r.data.size() > 0xFFFFFFFFu) return bad("a chunk is over 4 GiB");
  SerializedFile file;
  file.bytes = assemble_file(encode_header(c.header), body, &file.toc);
  return file;
}

}  // namespace dbss::format
