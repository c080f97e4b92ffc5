// Progressive decoding of a .dbss stream: feed bytes as they arrive, draw
// the finest level that is ready, refine when more arrives.
//
// Safe on untrusted input: the container reader checks every count against
// its Limits before allocating; the control mesh must have exactly the
// counts the header declares (so every later allocation is bounded by the
// header's checked counts), and no function throws or aborts.  The first
// error is sticky, but a container error (a damaged, malformed or cut chunk)
// voids nothing verified before it (spec section 11): ready_level() still
// counts those levels and decode() still returns them, while status() keeps
// reporting the error.  A decoder-side error (a bad control mesh) voids all.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "dbss/decoder/kernels.h"
#include "dbss/decoder/mesh.h"
#include "dbss/decoder/topology.h"
#include "dbss/format/reader.h"

namespace dbss {

struct DecoderOptions {
  format::Limits limits;
  // Threads for large levels; 0 = std::thread::hardware_concurrency().  The
  // output is the same for any value.  The decoder starts its helper threads
  // on the first large level and keeps them, asleep between levels, until it
  // is destroyed.
  unsigned threads = 0;
  // Keep every decoded level so going back to a coarser level costs nothing.
  // Off: only the control mesh and the current level are kept, and a coarser
  // level is recomputed from the control mesh.
  bool keep_levels = false;
  // Which build of the inner loops runs; the output is the same for any value.
  Kernels kernels = Kernels::best;
};

// A decoded level; the spans point into the decoder and stay valid until the
// next call to decode() or the decoder's destruction.
struct MeshView {
  uint32_t level = 0;
  std::span<const float> positions;     // 3 per vertex
  std::span<const uint32_t> triangles;  // 3 per triangle, counter-clockwise
  size_t vertex_count() const noexcept { return positions.size() / 3; }
  size_t triangle_count() const noexcept { return triangles.size() / 3; }
  TriangleMesh copy() const {
    return {std::vector<float>(positions.begin(), positions.end()),
            std::vector<uint32_t>(triangles.begin(), triangles.end())};
  }
};

class ProgressiveDecoder {
 public:
  explicit ProgressiveDecoder(const DecoderOptions& options = {});
  ~ProgressiveDecoder();
  ProgressiveDecoder(ProgressiveDecoder&&) noexcept;
  ProgressiveDecoder& operator=(ProgressiveDecoder&&) noexcept;

  // Parses `bytes` (any piece size).  Cheap: no subdivision happens here.
  Status feed(std::span<const uint8_t> bytes);
  // End of input; `truncated` if the file was cut, or the container's first
  // error.  Ready levels stay usable either way.
  Status finish();

  // The first error, or ok.
  const Status& status() const noexcept;
  const format::Reader& reader() const noexcept;

  // Finest level whose bytes are verified: -1 before the control mesh is in
  // (or after a decoder-side error).  Not lowered by a later container error.
  int ready_level() const noexcept;

  // Makes `level` (0..ready_level()) current and returns it.  Going finer
  // continues from the current level without recomputing coarser ones.
  Result<MeshView> decode(uint32_t level);
  Result<MeshView> decode_finest() { return decode(ready_level() < 0 ? 0 : static_cast<uint32_t>(ready_level())); }

  // Starts over for a new stream with the same options, as a new decoder
  // would, errors included.  The storage of the last level decoded is kept
  // for the new stream's levels (up to what that level used, and freed with
  // the decoder or at the next reset if unused): decoding many files with
  // one decoder skips most of the cost of fresh memory.  Spans from
  // earlier decode() calls are invalid afterwards.
  void reset();

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// Whole-file convenience: the mesh of `level` (or of the finest level in the
// file when level < 0).
Result<TriangleMesh> decode_bytes(std::span<const uint8_t> bytes, int level = -1, const DecoderOptions& options = {});

}  // namespace dbss
