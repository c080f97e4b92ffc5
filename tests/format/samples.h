// Sample container contents for the format tests.  The control payload is
// arbitrary bytes: the container does not look inside it.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "dbss/format/reader.h"
#include "dbss/format/writer.h"

namespace dbss::test {

// levels 1..L with pseudo-random q; level 2 uses varint coding.
inline format::FileContents sample_contents(uint32_t v, uint32_t e, uint32_t f, uint8_t levels, uint32_t seed = 1) {
  format::FileContents c;
  c.header.level_count = levels;
  c.header.control_vertex_count = v;
  c.header.control_edge_count = e;
  c.header.control_triangle_count = f;
  c.header.control_position_bits = 14;
  c.header.bbox_min = {-1.5f, -2.0f, -0.25f};
  c.header.bbox_max = {1.5f, 2.0f, 0.75f};
  c.header.error_target = 1e-4f;
  std::mt19937 rng(seed);
  c.control_mesh.resize(37 + seed % 11);
  for (auto& b : c.control_mesh) b = static_cast<uint8_t>(rng());
  const format::MeshCounts control{v, e, f};
  for (uint8_t l = 1; l <= levels; ++l) {
    format::Level level;
    level.index = l;
    level.coding = l == 2 ? format::DisplacementCoding::varint : format::DisplacementCoding::byte_planes;
    level.step = 0.01f / static_cast<float>(1 << l);
    level.q.resize(*format::odd_vertex_count(control, l));
    std::uniform_int_distribution<int32_t> d(-300, 300);
    for (auto& q : level.q) q = d(rng);
    // The extremes of the valid range, where there is room.
    if (level.q.size() >= 2) level.q[0] = format::kMaxAbsDisplacement, level.q[1] = -format::kMaxAbsDisplacement;
    c.levels.push_back(std::move(level));
  }
  c.metadata = {{"encoder", "dbss tests"}, {"source", "samples.h"}};
  return c;
}

// A tetrahedron's counts (V 4, E 6, F 4) with 3 levels: a few hundred bytes,
// small enough for exhaustive sweeps.
inline std::vector<uint8_t> small_file() { return format::serialize(sample_contents(4, 6, 4, 3)).value(); }
// The paper's genus-1 counts (V 50, E 150, F 100) with 3 levels.
inline std::vector<uint8_t> big_file() { return format::serialize(sample_contents(50, 150, 100, 3, 2)).value(); }

// A sample file with the table of contents the writer says it wrote: the
// expectations below come from the writer, not from the reader under test.
struct SampleFile {
  std::vector<uint8_t> bytes;
  std::vector<format::TocEntry> toc;
};
inline SampleFile small_sample() {
  auto f = format::serialize_with_toc(sample_contents(4, 6, 4, 3)).value();
  return {std::move(f.bytes), std::move(f.toc)};
}
inline SampleFile big_sample() {
  auto f = format::serialize_with_toc(sample_contents(50, 150, 100, 3, 2)).value();
  return {std::move(f.bytes), std::move(f.toc)};
}

// Number of LEVL chunks that end within the first `n` bytes.
inline uint32_t levels_within(const SampleFile& file, size_t n) {
  uint32_t count = 0;
  for (const auto& e : file.toc)
    if (e.type == format::kLevl && e.end() <= n) ++count;
  return count;
}

inline bool ends_within(const SampleFile& file, format::ChunkType type, size_t n) {
  for (const auto& e : file.toc)
    if (e.type == type) return e.end() <= n;
  return false;
}

}  // namespace dbss::test
