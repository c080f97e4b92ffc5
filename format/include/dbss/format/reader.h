// Reading .dbss containers as a push parser.
//
// Feed the bytes of a file in any pieces, down to one byte at a time; after
// each feed the reader tells which chunks are complete and verified (CRC32C
// and every field checked) and hands out their contents.  It copies what it
// needs out of each piece, so callers may reuse their buffers.
//
// Safe on untrusted input: every length and count is checked against the
// table of contents, the format's ranges and the Limits before anything is
// allocated for it, and memory grows only with bytes actually fed (plus the
// decompressed displacements of verified levels, bounded by Limits).  No
// function throws or aborts; the first error is sticky, as in libspng: a
// failed reader stays failed and reports the same Status.
//
// An error voids nothing verified before it (spec section 11): after a
// damaged or cut chunk, the header, the table of contents, the control
// payload, levels 1..levels_ready() and the metadata read so far stay
// available, and the status still reports the error.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dbss/format/container.h"
#include "dbss/format/status.h"

namespace dbss::format {

struct Limits {
  uint64_t max_file_size = uint64_t{1} << 32;     // bytes, as declared by the table of contents
  uint32_t max_levels = kMaxLevelsInPractice;     // LEVL chunks
  uint64_t max_vertices = uint64_t{1} << 26;      // vertices of the finest level
  uint32_t max_chunks = 4096;                     // entries in the table of contents
  uint32_t max_ancillary_bytes = 16u << 20;       // data bytes of any one ancillary chunk
  // Off only for fuzzing, so generated inputs reach the field checks behind
  // the CRC (as libspng's spng_set_crc_action); never off for real files.
  bool verify_checksums = true;
};

class Reader {
 public:
  explicit Reader(const Limits& limits = {});

  // Consumes all of `bytes`.  Returns the sticky error, or ok.  Running out
  // of bytes in the middle of a chunk is not an error here: call finish().
  Status feed(std::span<const uint8_t> bytes);
  // Declares the end of the input.  ok if the file is complete, otherwise a
  // `truncated` error naming the chunk that is cut; whatever was verified
  // before stays available either way.
  Status finish();

  const Status& status() const noexcept { return status_; }
  bool failed() const noexcept { return !status_.ok(); }
  // Bytes consumed so far (the offset of the next byte to be fed).
  uint64_t offset() const noexcept { return offset_; }
  // True once every chunk the table of contents lists is verified.
  bool complete() const noexcept;

  bool has_header() const noexcept { return has_header_; }
  const Header& header() const noexcept { return header_; }

  // The table of contents: the chunks after INDX, in file order.  Empty until
  // INDX is verified.  A client that has it can ask for any byte range.
  bool has_toc() const noexcept { return has_toc_; }
  const std::vector<TocEntry>& toc() const noexcept { return toc_; }
  // Declared size of the whole file (0 until INDX is verified).
  uint64_t file_size() const noexcept { return file_size_; }
  // How many leading TOC entries are complete and verified.
  size_t chunks_verified() const noexcept { return body_done_; }

  bool has_control() const noexcept { return has_control_; }
  ControlCodec control_codec() const noexcept { return control_codec_; }
  // The control mesh codec's bytes; valid while the reader lives.
  std::span<const uint8_t> control_payload() const noexcept { return control_payload_; }

  // The crease tags, once a CREA chunk is verified (version 1.1); until
  // then, and in files without one, empty.
  bool has_creases() const noexcept { return has_creases_; }
  const Creases& creases() const noexcept { return creases_; }
  // Levels 1..levels_ready() are verified and decompressed.
  uint32_t levels_ready() const noexcept { return static_cast<uint32_t>(levels_.size()); }
  // Level `index` in 1..levels_ready() (std::out_of_range otherwise: a
  // caller bug, never a property of the input).
  const Level& level(uint32_t index) const { return levels_.at(index - 1); }
  // Moves the displacements of a ready level out (to save memory); level()
  // afterwards has an empty q.
  Level take_level(uint32_t index) { return std::move(levels_.at(index - 1)); }

  // Entries of every verified 'meta' chunk, in file order.
  const std::vector<MetaEntry>& metadata() const noexcept { return metadata_; }
  // Verified ancillary chunks of types this reader does not know (skipped).
  size_t ancillary_skipped() const noexcept { return ancillary_skipped_; }
  // Problems that leave the file valid (spec section 10): a 'meta' chunk
  // whose CRC holds but whose entries are malformed is dropped whole, and
  // its bad_field status, with the offset of the problem, is kept here.
  const std::vector<Status>& warnings() const noexcept { return warnings_; }

 private:
  enum class Stage { signature, chunk_head, chunk_data, chunk_crc, done };

  Status feed_bytes(std::span<const uint8_t> bytes);
  Status fail(ErrorCode code, std::string message, uint64_t at);
  Status begin_chunk();
  Status end_chunk();
  Status on_head();
  Status on_toc();
  Status on_control();
  Status on_level();
  Status on_meta();
  Status on_creases();
  Status on_boundary();
  // The fields and payload of a LEVL or BDRY chunk (spec sections 9, 9c).
  Status parse_values(const char* kind, uint64_t expect, const char* count_name, const char* expect_says,
                      uint8_t codings, DisplacementCoding& coding, float& step, std::vector<int32_t>& q);
  std::string chunk_name() const;

  Limits limits_;
  Status status_;
  Stage stage_ = Stage::signature;
  uint64_t offset_ = 0;

  // The piece being gathered: signature, 8-byte chunk head, data or CRC.
  std::vector<uint8_t> buf_;
  size_t need_ = 0;

  // Current chunk.
  size_t chunk_index_ = 0;  // 0 = HEAD, 1 = INDX, 2.. = toc_[chunk_index_ - 2]
  uint64_t chunk_offset_ = 0;
  uint32_t chunk_length_ = 0;
  ChunkType chunk_type_;
  std::vector<uint8_t> chunk_data_;
  uint32_t running_crc_ = 0;

  bool has_header_ = false;
  Header header_;
  bool has_toc_ = false;
  std::vector<TocEntry> toc_;
  uint64_t file_size_ = 0;
  size_t body_done_ = 0;

  bool has_control_ = false;
  ControlCodec control_codec_ = ControlCodec::draco;
  std::vector<uint8_t> control_payload_;
  bool has_creases_ = false;
  Creases creases_;
  std::vector<Level> levels_;
  std::optional<BoundaryValues> pending_boundary_;  // a verified BDRY waiting for its LEVL
  std::vector<MetaEntry> metadata_;
  size_t ancillary_skipped_ = 0;
  std::vector<Status> warnings_;
};

// Convenience: feeds `bytes` whole and calls finish().  The returned reader
// holds either the complete file or a failed status.
Reader read_all(std::span<const uint8_t> bytes, const Limits& limits = {});

}  // namespace dbss::format
