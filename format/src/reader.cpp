#include "dbss/format/reader.h"

#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>

#include "byte_io.h"
#include "context_coding.h"
#include "dbss/format/crc32c.h"
#include "rules.h"

namespace dbss::format {

using namespace detail;

namespace {

constexpr uint32_t kMaxHeadSize = 1024;
constexpr uint32_t kLevelFixed = 16;  // LEVL bytes before the zstd frame

std::string hex32(uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%08X", v);
  return b;
}

// A chunk type as text that is safe to print even when the bytes are not letters.
std::string printable(const ChunkType& t) {
  std::string s;
  for (char ch : t.c) {
    const auto u = static_cast<unsigned char>(ch);
    if (u >= 0x20 && u < 0x7F) {
      s += ch;
    } else {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02X", u);
      s += b;
    }
  }
  return s;
}

}  // namespace

Reader::Reader(const Limits& limits) : limits_(limits) {}

bool Reader::complete() const noexcept { return stage_ == Stage::done && status_.ok(); }

Status Reader::fail(ErrorCode code, std::string message, uint64_t at) {
  status_ = Status(code, std::move(message), at);
  return status_;
}

std::string Reader::chunk_name() const {
  if (chunk_index_ == 0) return "chunk 'HEAD'";
  if (chunk_index_ == 1) return "chunk 'INDX'";
  return "chunk '" + printable(chunk_type_) + "' (entry " + std::to_string(chunk_index_ - 2) + " of the table of contents)";
}

Status Reader::feed(std::span<const uint8_t> bytes) {
  if (failed()) return status_;
  // Every size is bounded by Limits before anything is allocated, but the
  // limits are the caller's choice: running out of memory must still come
  // back as a value.
  try {
    return feed_bytes(bytes);
  } catch (const std::bad_alloc&) {
    return fail(ErrorCode::limit_exceeded, "out of memory while reading " + chunk_name(), offset_);
  }
}

Status Reader::feed_bytes(std::span<const uint8_t> bytes) {
  size_t i = 0;
  const size_t n = bytes.size();
  while (i < n) {
    switch (stage_) {
      case Stage::signature: {
        // Compared byte by byte so a wrong file fails on its first wrong byte.
        const uint8_t b = bytes[i];
        if (b != kSignature[offset_])
          return fail(ErrorCode::bad_signature,
                      "not a .dbss file: signature byte " + std::to_string(offset_) + " is " + std::to_string(b) +
                          ", expected " + std::to_string(kSignature[offset_]),
                      offset_);
        ++i;
        ++offset_;
        if (offset_ == kSignature.size()) {
          stage_ = Stage::chunk_head;
          need_ = 8;
          buf_.clear();
        }
        break;
      }
      case Stage::chunk_head:
      case Stage::chunk_crc: {
        const size_t take = std::min(need_ - buf_.size(), n - i);
        buf_.insert(buf_.end(), bytes.begin() + i, bytes.begin() + i + take);
        i += take;
        offset_ += take;
        if (buf_.size() == need_) {
          Status s = stage_ == Stage::chunk_head ? begin_chunk() : end_chunk();
          if (!s.ok()) return s;
        }
        break;
      }
      case Stage::chunk_data: {
        const size_t take = static_cast<size_t>(std::min<uint64_t>(chunk_length_ - chunk_data_.size(), n - i));
        chunk_data_.insert(chunk_data_.end(), bytes.begin() + i, bytes.begin() + i + take);
        i += take;
        offset_ += take;
        if (chunk_data_.size() == chunk_length_) {
          stage_ = Stage::chunk_crc;
          need_ = 4;
          buf_.clear();
        }
        break;
      }
      case Stage::done:
        return fail(ErrorCode::trailing_data,
                    "data after the end of the file declared by the table of contents (" +
                        std::to_string(file_size_) + " bytes)",
                    offset_);
    }
  }
  return status_;
}

Status Reader::begin_chunk() {
  chunk_offset_ = offset_ - 8;
  chunk_length_ = load_u32(buf_.data());
  std::copy(buf_.begin() + 4, buf_.begin() + 8, chunk_type_.c.begin());
  running_crc_ = crc32c(std::span<const uint8_t>(buf_.data(), 8));
  const uint64_t at = chunk_offset_;

  if (chunk_index_ == 0) {
    if (!(chunk_type_ == kHead))
      return fail(ErrorCode::bad_structure, "the first chunk must be 'HEAD', found '" + printable(chunk_type_) + "'", at);
    if (chunk_length_ < kHeadSize || chunk_length_ > kMaxHeadSize)
      return fail(ErrorCode::bad_structure,
                  "chunk 'HEAD' has length " + std::to_string(chunk_length_) + ", expected 56..1024", at);
  } else if (chunk_index_ == 1) {
    if (!(chunk_type_ == kIndx))
      return fail(ErrorCode::bad_structure,
                  "the second chunk must be 'INDX', found '" + printable(chunk_type_) + "'", at);
    if (chunk_length_ < 32 || (chunk_length_ - 16) % 16 != 0)
      return fail(ErrorCode::bad_structure,
                  "chunk 'INDX' has length " + std::to_string(chunk_length_) + ", expected 16 + 16 * entries", at);
    if ((chunk_length_ - 16) / 16 > limits_.max_chunks)
      return fail(ErrorCode::limit_exceeded,
                  "table of contents lists " + std::to_string((chunk_length_ - 16) / 16) + " chunks, over the limit of " +
                      std::to_string(limits_.max_chunks),
                  at);
  } else {
    const TocEntry& e = toc_[chunk_index_ - 2];
    if (!(chunk_type_ == e.type) || chunk_length_ != e.length || chunk_offset_ != e.offset)
      return fail(ErrorCode::bad_structure,
                  "chunk '" + printable(chunk_type_) + "' of length " + std::to_string(chunk_length_) +
                      " where the table of contents lists '" + printable(e.type) + "' of length " +
                      std::to_string(e.length),
                  at);
  }
  // No reserve(length): the buffer grows only with bytes that really arrive.
  chunk_data_.clear();
  if (chunk_length_ == 0) {
    stage_ = Stage::chunk_crc;
    need_ = 4;
  } else {
    stage_ = Stage::chunk_data;
  }
  buf_.clear();
  return {};
}

Status Reader::end_chunk() {
  const uint32_t stored = load_u32(buf_.data());
  const uint32_t actual = crc32c_extend(running_crc_, chunk_data_);
  if (stored != actual && limits_.verify_checksums)
    return fail(ErrorCode::checksum_mismatch,
                chunk_name() + " at byte " + std::to_string(chunk_offset_) + " is damaged: stored CRC32C " +
                    hex32(stored) + ", computed " + hex32(actual),
                offset_ - 4);

  Status s;
  if (chunk_index_ == 0) {
    s = on_head();
  } else if (chunk_index_ == 1) {
    s = on_toc();
  } else if (chunk_type_ == kCtrl) {
    s = on_control();
  } else if (chunk_type_ == kLevl) {
    s = on_level();
  } else if (chunk_type_ == kMeta) {
    s = on_meta();
  } else if (chunk_type_ == kCrea) {
    s = on_creases();
  } else if (chunk_type_ == kBdry) {
    s = on_boundary();
  } else {
    ++ancillary_skipped_;  // unknown critical types were refused with the table of contents
  }
  if (!s.ok()) return s;

  if (chunk_index_ >= 2) ++body_done_;
  ++chunk_index_;
  chunk_data_ = {};
  buf_.clear();
  if (chunk_index_ >= 2 && body_done_ == toc_.size()) {
    stage_ = Stage::done;
  } else {
    stage_ = Stage::chunk_head;
    need_ = 8;
  }
  return {};
}

Status Reader::on_head() {
  const uint8_t* d = chunk_data_.data();
  const uint64_t at = chunk_offset_ + 8;
  Header h;
  h.version_major = load_u16(d);
  h.version_minor = load_u16(d + 2);
  h.flags = load_u32(d + 4);
  h.level_count = d[8];
  h.displacement_mode = d[9];
  h.control_position_bits = d[10];
  h.control_vertex_count = load_u32(d + 12);
  h.control_edge_count = load_u32(d + 16);
  h.control_triangle_count = load_u32(d + 20);
  for (int k = 0; k < 3; ++k) {
    h.bbox_min[k] = load_f32(d + 24 + 4 * k);
    h.bbox_max[k] = load_f32(d + 36 + 4 * k);
  }
  h.error_target = load_f32(d + 48);
  // Spec section 12 fixes the order, so every reader gives an invalid file
  // the same code: the version, then the length the version implies, then
  // the fields and the 2^62 bound (the file's own rules), and only then this
  // reader's limits, so the code of an invalid file never depends on them.
  const Status fields = check_header(h, at);
  if (fields.code() == ErrorCode::unsupported_version) return fail(fields.code(), fields.message(), at);
  if (h.version_minor == 0 && chunk_length_ != kHeadSize)
    return fail(ErrorCode::bad_structure, "HEAD of version 1.0 must be 56 bytes long", chunk_offset_);
  if (!fields.ok()) return fail(fields.code(), fields.message(), at);
  if (d[11] != 0 || load_u32(d + 52) != 0) return fail(ErrorCode::bad_field, "HEAD: reserved bytes are not zero", at);
  const auto finest = counts_at_level({h.control_vertex_count, h.control_edge_count, h.control_triangle_count},
                                      h.level_count);
  if (!finest)
    return fail(ErrorCode::bad_field,
                "HEAD: a count of level " + std::to_string(h.level_count) + " passes 2^62", at);
  if (h.level_count > limits_.max_levels)
    return fail(ErrorCode::limit_exceeded,
                "file has " + std::to_string(h.level_count) + " levels, over the limit of " +
                    std::to_string(limits_.max_levels),
                at + 8);
  if (finest->vertices > limits_.max_vertices)
    return fail(ErrorCode::limit_exceeded,
                "level " + std::to_string(h.level_count) + " would have " + std::to_string(finest->vertices) +
                    " vertices, over the limit of " + std::to_string(limits_.max_vertices),
                at);
  header_ = h;
  has_header_ = true;
  return {};
}

Status Reader::on_toc() {
  const uint8_t* d = chunk_data_.data();
  const uint64_t at = chunk_offset_ + 8;
  const uint64_t file_size = load_u64(d);
  const uint32_t count = load_u32(d + 8);
  if (count != (chunk_length_ - 16) / 16)
    return fail(ErrorCode::bad_structure,
                "INDX: entry_count " + std::to_string(count) + " disagrees with the chunk length", at + 8);
  if (load_u32(d + 12) != 0) return fail(ErrorCode::bad_field, "INDX: reserved field is not zero", at + 12);

  std::vector<TocEntry> toc;
  toc.reserve(count);  // count <= max_chunks, checked in begin_chunk
  uint64_t expect = offset_;
  uint32_t controls = 0, levels = 0, creases = 0;
  bool boundary_seen = false, boundary_pending = false;  // rule 9: a BDRY waits for its LEVL
  for (uint32_t i = 0; i < count; ++i) {
    const uint8_t* p = d + 16 + 16 * size_t{i};
    const uint64_t eat = at + 16 + 16 * uint64_t{i};
    TocEntry e;
    std::copy(p, p + 4, e.type.c.begin());
    e.length = load_u32(p + 4);
    e.offset = load_u64(p + 8);
    const std::string name = "INDX entry " + std::to_string(i) + " ('" + printable(e.type) + "')";
    if (!e.type.well_formed()) return fail(ErrorCode::bad_structure, name + ": type is not four ASCII letters", eat);
    if (e.offset != expect)
      return fail(ErrorCode::bad_structure,
                  name + ": offset " + std::to_string(e.offset) + ", expected " + std::to_string(expect), eat + 8);
    if (e.end() > file_size)
      return fail(ErrorCode::bad_structure, name + ": ends past the declared file size", eat + 4);
    expect = e.end();
    if (e.type == kHead || e.type == kIndx)
      return fail(ErrorCode::bad_structure, name + ": HEAD and INDX may appear only once, first", eat);
    if (e.type == kCtrl) {
      if (++controls > 1) return fail(ErrorCode::bad_structure, name + ": a second CTRL chunk", eat);
    } else if (e.type == kLevl) {
      if (controls == 0) return fail(ErrorCode::bad_structure, name + ": LEVL before CTRL", eat);
      ++levels;
      boundary_pending = false;
    } else if (e.type == kBdry && header_.version_minor >= kBoundaryVersionMinor) {
      // Version 1.3: after CTRL, at most one per level, before its LEVL.
      if (controls == 0) return fail(ErrorCode::bad_structure, name + ": BDRY before CTRL", eat);
      if (boundary_pending) return fail(ErrorCode::bad_structure, name + ": a second BDRY for one level", eat);
      boundary_pending = boundary_seen = true;
    } else if (e.type == kCrea && header_.version_minor >= kCreaseVersionMinor) {
      // Version 1.1: at most one, after CTRL, before every LEVL (level 1 needs it).
      if (++creases > 1) return fail(ErrorCode::bad_structure, name + ": a second CREA chunk", eat);
      if (controls == 0 || levels > 0 || boundary_seen)
        return fail(ErrorCode::bad_structure, name + ": CREA must come after CTRL and before every LEVL and BDRY", eat);
    } else if (e.type.critical()) {
      // CREA in a file that says 1.0 is as unknown as to a 1.0 reader.
      return fail(ErrorCode::unknown_critical_chunk,
                  name + ": critical chunk type unknown to this reader in a file of version 1." +
                      std::to_string(header_.version_minor),
                  eat);
    }
    toc.push_back(e);
  }
  if (controls != 1) return fail(ErrorCode::bad_structure, "INDX: the file has no CTRL chunk", at);
  if (levels != header_.level_count)
    return fail(ErrorCode::bad_structure,
                "INDX lists " + std::to_string(levels) + " LEVL chunks but HEAD declares " +
                    std::to_string(header_.level_count),
                at);
  if (boundary_pending) return fail(ErrorCode::bad_structure, "INDX: a BDRY chunk after the last LEVL", at);
  if (expect != file_size)
    return fail(ErrorCode::bad_structure,
                "INDX: file_size " + std::to_string(file_size) + " but the chunks end at " + std::to_string(expect), at);
  // This reader's limits come after the format's rules (spec section 12):
  // a table that breaks both is reported as broken, whatever the limits.
  if (file_size > limits_.max_file_size)
    return fail(ErrorCode::limit_exceeded,
                "file declares " + std::to_string(file_size) + " bytes, over the limit of " +
                    std::to_string(limits_.max_file_size),
                at);
  for (size_t i = 0; i < toc.size(); ++i) {
    const TocEntry& e = toc[i];
    if (!e.type.critical() && e.length > limits_.max_ancillary_bytes)
      return fail(ErrorCode::limit_exceeded,
                  "INDX entry " + std::to_string(i) + " ('" + printable(e.type) + "'): " + std::to_string(e.length) +
                      " bytes, over the ancillary limit of " + std::to_string(limits_.max_ancillary_bytes),
                  at + 16 + 16 * uint64_t{i} + 4);
  }
  toc_ = std::move(toc);
  file_size_ = file_size;
  has_toc_ = true;
  return {};
}

Status Reader::on_control() {
  const uint64_t at = chunk_offset_ + 8;
  if (chunk_length_ < 5) return fail(ErrorCode::bad_field, "CTRL: no control mesh bytes", at);
  if (chunk_data_[0] != static_cast<uint8_t>(ControlCodec::draco))
    return fail(ErrorCode::bad_field, "CTRL: unknown codec " + std::to_string(chunk_data_[0]), at);
  if (chunk_data_[1] | chunk_data_[2] | chunk_data_[3])
    return fail(ErrorCode::bad_field, "CTRL: reserved bytes are not zero", at + 1);
  control_codec_ = ControlCodec::draco;
  control_payload_.assign(chunk_data_.begin() + 4, chunk_data_.end());
  has_control_ = true;
  return {};
}

Status Reader::on_level() {
  Level level;
  const uint32_t index = levels_ready() + 1;
  // Coding 2 is new in 1.2: in an older file it is unknown, as a 1.1 reader finds it.
  const uint8_t codings = header_.version_minor >= kContextCodingVersionMinor ? 3 : 2;
  const MeshCounts control{header_.control_vertex_count, header_.control_edge_count, header_.control_triangle_count};
  const auto expect = odd_vertex_count(control, index);  // cannot overflow: HEAD was checked
  if (Status s = parse_values("LEVL", expect.value_or(0), "odd_count", "the control mesh implies", codings,
                              level.coding, level.step, level.q);
      !s.ok())
    return s;
  level.index = static_cast<uint8_t>(index);
  if (pending_boundary_) {
    level.boundary = std::move(*pending_boundary_);
    pending_boundary_.reset();
  }
  levels_.push_back(std::move(level));
  return {};
}

Status Reader::on_boundary() {
  // Section 9c: laid out and checked as a LEVL, one value per boundary edge
  // of the level before the LEVL that follows.
  BoundaryValues b;
  const MeshCounts control{header_.control_vertex_count, header_.control_edge_count, header_.control_triangle_count};
  const auto expect = boundary_edge_count(control, levels_ready());
  if (Status s = parse_values("BDRY", expect.value_or(0), "boundary_count", "the boundary edges are", 3, b.coding,
                              b.step, b.q);
      !s.ok())
    return s;
  pending_boundary_ = std::move(b);
  return {};
}

Status Reader::parse_values(const char* kind, uint64_t expect, const char* count_name, const char* expect_says,
                            uint8_t codings, DisplacementCoding& coding_out, float& step, std::vector<int32_t>& q) {
  const uint8_t* d = chunk_data_.data();
  const uint64_t at = chunk_offset_ + 8;
  const uint32_t expected_index = levels_ready() + 1;
  const std::string name = std::string(kind) + " " + std::to_string(expected_index);
  // Spec section 9 lists these checks in this order with one code each.  A
  // 16-byte chunk has all its fields and an empty frame: a zstd error below.
  if (chunk_length_ < kLevelFixed)
    return fail(ErrorCode::bad_field,
                name + ": " + std::to_string(chunk_length_) + " bytes, too short for its 16 bytes of fields", at);
  const uint8_t index = d[0];
  const uint8_t coding = d[1];
  const uint32_t count = load_u32(d + 4);
  step = load_f32(d + 8);
  const uint32_t raw_size = load_u32(d + 12);
  if (index != expected_index)
    return fail(ErrorCode::bad_structure, name + ": level index field is " + std::to_string(index), at);
  if (coding >= codings)
    return fail(ErrorCode::bad_field, name + ": unknown coding " + std::to_string(coding), at + 1);
  coding_out = static_cast<DisplacementCoding>(coding);
  if (load_u16(d + 2) != 0) return fail(ErrorCode::bad_field, name + ": reserved field is not zero", at + 2);
  // A BDRY of a level without boundary edges is invalid whatever it says.
  if (count != expect || expect == 0)
    return fail(ErrorCode::bad_field,
                name + ": " + count_name + " " + std::to_string(count) + ", but " + expect_says + " " +
                    std::to_string(expect),
                at + 4);
  if (!std::isfinite(step) || !(step > 0))
    return fail(ErrorCode::bad_field, name + ": step is not a finite positive number", at + 8);
  if (!raw_size_valid(raw_size, coding_out, count))
    return fail(ErrorCode::bad_field, name + ": raw_size " + std::to_string(raw_size) + " does not fit " +
                                          std::to_string(count) + " values",
                at + 12);

  const uint8_t* src = d + kLevelFixed;
  const size_t src_size = chunk_length_ - kLevelFixed;
  if (coding_out == DisplacementCoding::context) {
    if (raw_size != src_size)
      return fail(ErrorCode::bad_field,
                  name + ": raw_size " + std::to_string(raw_size) + " is not the coded stream's " +
                      std::to_string(src_size) + " bytes",
                  at + 12);
    if (Status s = context_decode({src, src_size}, count, at + kLevelFixed, q); !s.ok())
      return fail(s.code(), name + ": " + s.message(), s.offset());
    return {};
  }
  const size_t frame = ZSTD_findFrameCompressedSize(src, src_size);
  if (ZSTD_isError(frame) || frame != src_size)
    return fail(ErrorCode::compression, name + ": payload is not exactly one zstd frame", at + kLevelFixed);
  const unsigned long long declared = ZSTD_getFrameContentSize(src, src_size);
  if (declared == ZSTD_CONTENTSIZE_ERROR)
    return fail(ErrorCode::compression, name + ": bad zstd frame header", at + kLevelFixed);
  if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != raw_size)
    return fail(ErrorCode::compression, name + ": zstd frame holds " + std::to_string(declared) + " bytes, raw_size says " +
                                          std::to_string(raw_size),
                at + kLevelFixed);
  // raw_size <= 4 * count and count is bounded by max_vertices via HEAD.
  std::vector<uint8_t> raw(raw_size);
  const size_t got = ZSTD_decompress(raw.data(), raw.size(), src, src_size);
  if (ZSTD_isError(got))
    return fail(ErrorCode::compression, name + ": zstd: " + ZSTD_getErrorName(got), at + kLevelFixed);
  if (got != raw_size)
    return fail(ErrorCode::compression, name + ": zstd frame decompressed to " + std::to_string(got) + " bytes, not " +
                                            std::to_string(raw_size),
                at + kLevelFixed);
  if (Status s = unpack_displacements(raw, coding_out, count, at + kLevelFixed, q); !s.ok())
    return fail(s.code(), name + ": " + s.message(), s.offset());
  return {};
}

Status Reader::on_creases() {
  Creases c;
  if (Status s = parse_creases(chunk_data_, header_.control_edge_count, header_.control_vertex_count,
                               chunk_offset_ + 8, c);
      !s.ok())
    return fail(s.code(), s.message(), s.offset());
  creases_ = std::move(c);
  has_creases_ = true;
  return {};
}

Status Reader::on_meta() {
  // 'meta' is ancillary (spec section 10): a reader that skips it must reach
  // the same verdict on the file as one that parses it, so a malformed one
  // is dropped whole with a warning, never an error.
  std::vector<MetaEntry> entries;
  if (Status s = parse_meta(chunk_data_, chunk_offset_ + 8, entries); !s.ok()) {
    warnings_.push_back(std::move(s));
    return {};
  }
  for (auto& e : entries) metadata_.push_back(std::move(e));
  return {};
}

Status Reader::finish() {
  if (failed()) return status_;
  if (stage_ == Stage::done) return status_;
  std::string where;
  switch (stage_) {
    case Stage::signature: where = "inside the signature"; break;
    case Stage::chunk_head:
      where = chunk_index_ >= 2 ? "before the end of chunk entry " + std::to_string(chunk_index_ - 2) +
                                      " ('" + printable(toc_[chunk_index_ - 2].type) + "')"
                                : (chunk_index_ == 0 ? "before chunk 'HEAD' is complete" : "before chunk 'INDX' is complete");
      break;
    case Stage::chunk_data:
    case Stage::chunk_crc: where = "inside " + chunk_name(); break;
    case Stage::done: break;
  }
  std::string total = has_toc_ ? " of " + std::to_string(file_size_) + " declared bytes" : "";
  return fail(ErrorCode::truncated,
              "file ends after " + std::to_string(offset_) + total + ", " + where + "; " +
                  std::to_string(levels_ready()) + " of " + std::to_string(header_.level_count) + " levels complete",
              offset_);
}

Reader read_all(std::span<const uint8_t> bytes, const Limits& limits) {
  Reader r(limits);
  if (r.feed(bytes).ok()) r.finish();
  return r;
}

}  // namespace dbss::format
