// libFuzzer target: the whole decode, every level, on arbitrary bytes.
//
// The first input byte sets the policy: bit 0 turns checksum verification
// off (so mutated files reach the field and mesh checks behind the CRC);
// the rest is the file, fed whole when the second byte is 0, else in pieces
// of random sizes (1..256 bytes) from a generator the second byte seeds.
// Oracles (always on): levels never exceed what the header declares, every
// decoded level has the counts the header implies, and decoding a level
// twice, or again after reset(), gives the same bits.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <span>

#include "dbss/decoder/progressive.h"

namespace {
void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "decode_fuzzer: oracle failed: %s\n", what);
    std::abort();
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  dbss::DecoderOptions o;
  o.limits.max_vertices = 1 << 18;  // bounded work per input
  o.limits.verify_checksums = !(data[0] & 1);
  o.threads = 1;
  const std::span<const uint8_t> file(data + 2, size - 2);
  dbss::ProgressiveDecoder d(o);
  uint32_t state = 0x9E3779B9u ^ data[1];
  for (size_t at = 0; at < file.size();) {
    size_t piece = file.size();
    if (data[1] != 0) {
      state ^= state << 13, state ^= state >> 17, state ^= state << 5;  // xorshift32
      piece = 1 + state % 256;
    }
    piece = std::min(piece, file.size() - at);
    if (!d.feed(file.subspan(at, piece)).ok()) break;
    at += piece;
  }
  d.finish();
  const int ready = d.ready_level();
  if (ready < 0) return 0;
  const auto& h = d.reader().header();
  check(ready <= h.level_count, "more levels ready than declared");
  const dbss::format::MeshCounts control{h.control_vertex_count, h.control_edge_count, h.control_triangle_count};
  for (int l = 0; l <= ready; ++l) {
    auto m = d.decode(static_cast<uint32_t>(l));
    if (!m.ok()) return 0;  // a bad control mesh is an error, not a crash
    const auto counts = dbss::format::counts_at_level(control, static_cast<uint32_t>(l));
    check(counts && m.value().vertex_count() == counts->vertices, "vertex count differs from the header's");
    check(m.value().triangle_count() == counts->triangles, "triangle count differs from the header's");
  }
  // Going back to level 0 and up again reproduces the same bits.
  auto finest = d.decode(static_cast<uint32_t>(ready));
  if (!finest.ok()) return 0;
  const auto first = finest.value().copy();
  d.decode(0);
  auto again = d.decode(static_cast<uint32_t>(ready));
  check(again.ok() && std::memcmp(again.value().positions.data(), first.positions.data(), first.positions.size() * 4) == 0,
        "re-decoding a level changed its bits");
  // A reset decoder decodes the same stream to the same bits, from the
  // storage it kept.
  d.reset();
  d.feed(file);  // whole: the same errors at the same bytes as the pieces
  d.finish();
  check(d.ready_level() == ready, "a reset decoder read the stream differently");
  auto reused = d.decode(static_cast<uint32_t>(ready));
  check(reused.ok() && std::memcmp(reused.value().positions.data(), first.positions.data(), first.positions.size() * 4) == 0,
        "a reset decoder changed the bits");
  return 0;
}
