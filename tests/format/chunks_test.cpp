#include <catch2/catch.hpp>

#include <zstd.h>

#include <cstring>
#include <limits>

#include "samples.h"

using namespace dbss;
using namespace dbss::format;

namespace {
// A LEVL chunk's data for level 1, by hand: `count` odd vertices, step 0.5,
// `raw` (the coded values before zstd) compressed as one frame.
std::vector<uint8_t> level_chunk(uint8_t coding_id, uint32_t count, const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> d = {1, coding_id, 0, 0};
  const auto put32 = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) d.push_back(static_cast<uint8_t>(v >> (8 * i)));
  };
  const float step = 0.5f;
  uint32_t bits;
  std::memcpy(&bits, &step, 4);
  put32(count), put32(bits), put32(static_cast<uint32_t>(raw.size()));
  std::vector<uint8_t> z(ZSTD_compressBound(raw.size()));
  z.resize(ZSTD_compress(z.data(), z.size(), raw.data(), raw.size(), 1));
  d.insert(d.end(), z.begin(), z.end());
  return d;
}

// Body chunks of a valid 2-level file, to rearrange.
struct Parts {
  Header header;
  RawChunk ctrl, level1, level2, meta;
};
Parts parts() {
  const FileContents c = test::sample_contents(50, 150, 100, 2);
  Parts p;
  p.header = c.header;
  p.ctrl = {kCtrl, encode_control(ControlCodec::draco, c.control_mesh)};
  p.level1 = {kLevl, encode_level(c.levels[0], 3).value()};
  p.level2 = {kLevl, encode_level(c.levels[1], 3).value()};
  p.meta = {kMeta, encode_metadata(c.metadata).value()};
  return p;
}
Reader read(const Header& h, std::vector<RawChunk> body) {
  const auto file = assemble(encode_header(h), body);
  return read_all(file);
}
}  // namespace

TEST_CASE("assembled valid chunks read back, and an unknown ancillary chunk is skipped") {
  const Parts p = parts();
  CHECK(read(p.header, {p.ctrl, p.level1, p.level2, p.meta}).complete());
  const RawChunk extra{ChunkType('x', 't', 'r', 'a'), {1, 2, 3, 4, 5}};
  const Reader r = read(p.header, {extra, p.ctrl, p.level1, extra, p.level2, p.meta});
  REQUIRE(r.complete());
  CHECK(r.ancillary_skipped() == 2);
  CHECK(r.levels_ready() == 2);
  CHECK(r.metadata().size() == 2);
}

TEST_CASE("an unknown critical chunk is rejected when the table of contents is read") {
  const Parts p = parts();
  const RawChunk extra{ChunkType('X', 't', 'r', 'a'), {1, 2, 3}};
  const auto file = assemble(encode_header(p.header), std::vector<RawChunk>{p.ctrl, p.level1, extra, p.level2});
  Reader r;
  // The whole INDX chunk is enough to refuse the file.
  const size_t indx_end = 8 + kChunkOverhead + kHeadSize + kChunkOverhead + 16 + 16 * 4;
  CHECK(r.feed(std::span<const uint8_t>(file.data(), indx_end)).code() == ErrorCode::unknown_critical_chunk);
  CHECK(r.status().offset() > 8 + kChunkOverhead + kHeadSize);
  CHECK(r.status().offset() < indx_end);
}

TEST_CASE("chunk order and counts are enforced") {
  const Parts p = parts();
  auto code = [&](std::vector<RawChunk> body, Header h) { return read(h, std::move(body)).status().code(); };
  CHECK(code({p.level1, p.ctrl, p.level2}, p.header) == ErrorCode::bad_structure);          // LEVL before CTRL
  CHECK(code({p.ctrl, p.level2, p.level1}, p.header) == ErrorCode::bad_structure);          // levels swapped
  CHECK(code({p.ctrl, p.ctrl, p.level1, p.level2}, p.header) == ErrorCode::bad_structure);  // two CTRL
  CHECK(code({p.ctrl, p.level1}, p.header) == ErrorCode::bad_structure);                    // one level missing
  CHECK(code({p.level1, p.level2}, p.header) == ErrorCode::bad_structure);                  // no CTRL
  CHECK(code({p.ctrl, p.level1, p.level2, {kHead, encode_header(p.header)}}, p.header) == ErrorCode::bad_structure);
  // A level whose odd count disagrees with the header's counts.
  Header other = p.header;
  other.control_edge_count = 151;
  other.control_triangle_count = 100;
  CHECK(code({p.ctrl, p.level1, p.level2}, other) == ErrorCode::bad_field);
}

TEST_CASE("header fields out of range") {
  const Parts p = parts();
  auto code = [&](Header h) { return read(h, {p.ctrl, p.level1, p.level2}).status().code(); };
  Header h = p.header;
  h.version_major = 2;
  CHECK(code(h) == ErrorCode::unsupported_version);
  h = p.header;
  h.flags = 4;
  CHECK(code(h) == ErrorCode::bad_field);
  h = p.header;
  h.displacement_mode = 1;
  CHECK(code(h) == ErrorCode::bad_field);
  h = p.header;
  h.bbox_max[2] = std::numeric_limits<float>::infinity();
  CHECK(code(h) == ErrorCode::bad_field);
  // Reserved bytes: patch byte 11 of HEAD's data, then fix the CRC.
  auto file = assemble(encode_header(p.header), std::vector<RawChunk>{p.ctrl, p.level1, p.level2});
  auto head = encode_header(p.header);
  head[11] = 1;
  auto patched = assemble(head, std::vector<RawChunk>{p.ctrl, p.level1, p.level2});
  CHECK(read_all(patched).status().code() == ErrorCode::bad_field);
  CHECK(read_all(file).complete());
}

TEST_CASE("a table-of-contents entry that disagrees with its chunk is refused") {
  const Parts p = parts();
  auto file = assemble(encode_header(p.header), std::vector<RawChunk>{p.ctrl, p.level1, p.level2});
  // Re-assemble with a longer CTRL, then splice the original INDX in front:
  // lengths now disagree and every CRC is still valid.
  RawChunk longer = p.ctrl;
  longer.data.push_back(0);
  auto other = assemble(encode_header(p.header), std::vector<RawChunk>{longer, p.level1, p.level2});
  const size_t body = 8 + kChunkOverhead + kHeadSize + kChunkOverhead + 16 + 16 * 3;
  std::vector<uint8_t> spliced(file.begin(), file.begin() + body);
  spliced.insert(spliced.end(), other.begin() + body, other.end());
  const Reader r = read_all(spliced);
  CHECK(r.status().code() == ErrorCode::bad_structure);
  CHECK(r.status().offset() == body);
}

TEST_CASE("level payload rules: non-canonical varints, bad raw_size, two zstd frames") {
  const FileContents c = test::sample_contents(4, 6, 4, 1);
  auto level = c.levels[0];
  level.coding = DisplacementCoding::varint;
  auto data = encode_level(level, 3).value();
  // raw_size under odd_count is impossible for varints.
  auto bad_raw = data;
  bad_raw[12] = 1, bad_raw[13] = bad_raw[14] = bad_raw[15] = 0;
  Header h = c.header;
  auto file_of = [&](std::vector<uint8_t> d) {
    return read_all(assemble(encode_header(h), std::vector<RawChunk>{{kCtrl, encode_control(ControlCodec::draco, c.control_mesh)}, {kLevl, d}}));
  };
  CHECK(file_of(data).complete());
  CHECK(file_of(bad_raw).status().code() == ErrorCode::bad_field);
  // A second frame after the first.
  auto two = data;
  two.insert(two.end(), data.begin() + 16, data.end());
  CHECK(file_of(two).status().code() == ErrorCode::compression);
  // Unknown coding.
  auto coding = data;
  coding[1] = 7;
  CHECK(file_of(coding).status().code() == ErrorCode::bad_field);

  // Hand-made payloads: the 6 odd vertices of level 1 of a tetrahedron.
  auto level_data = [](uint8_t coding_id, const std::vector<uint8_t>& raw) { return level_chunk(coding_id, 6, raw); };
  CHECK(file_of(level_data(1, {0, 1, 2, 3, 4, 5})).complete());
  CHECK(file_of(level_data(1, {0x80, 0x00, 1, 2, 3, 4, 5})).status().code() == ErrorCode::bad_field);  // not shortest
  CHECK(file_of(level_data(1, {0x80, 0x80, 0x80, 0x80, 0x01, 1, 2, 3, 4, 5})).status().code() == ErrorCode::bad_field);
  CHECK(file_of(level_data(1, {0, 1, 2, 3, 4, 5, 6})).status().code() == ErrorCode::bad_field);  // left-over byte
  // Byte planes: z = 2^25 + 2 (q just past 2^24) in the first value.
  std::vector<uint8_t> planes(24, 0);
  planes[0] = 2, planes[18] = 2;
  CHECK(file_of(level_data(0, planes)).status().code() == ErrorCode::bad_field);
  planes[0] = 0;  // z = 2^25 exactly: q = 2^24, valid
  const Reader ok = file_of(level_data(0, planes));
  REQUIRE(ok.complete());
  CHECK(ok.level(1).q[0] == kMaxAbsDisplacement);
}

TEST_CASE("varint limits: four bytes up to q = 2^24 read, past the range or over four bytes refused by name") {
  const FileContents c = test::sample_contents(4, 6, 4, 1);
  const auto file_of = [&](const std::vector<uint8_t>& raw) {
    return read_all(assemble(encode_header(c.header), std::vector<RawChunk>{{kCtrl, encode_control(ControlCodec::draco, c.control_mesh)},
                                                                            {kLevl, level_chunk(1, 6, raw)}}));
  };
  // z = 2^25 (four bytes, 0x80 0x80 0x80 0x10): q = 2^24, the largest.
  const Reader ok = file_of({0x80, 0x80, 0x80, 0x10, 1, 2, 3, 4, 5});
  REQUIRE(ok.complete());
  CHECK(ok.level(1).q[0] == kMaxAbsDisplacement);
  CHECK(ok.level(1).q[5] == -3);
  // z = 2^25 + 2 (0x82 0x80 0x80 0x10): q = 2^24 + 1, outside the range.
  const Reader big = file_of({0x82, 0x80, 0x80, 0x10, 1, 2, 3, 4, 5});
  CHECK(big.status().code() == ErrorCode::bad_field);
  CHECK_THAT(big.status().message(), Catch::Contains("#0 is outside -2^24..2^24"));
  // Five bytes: refused as too long before its value is looked at.
  const Reader longer = file_of({1, 0x80, 0x80, 0x80, 0x80, 0x01, 2, 3, 4, 5});
  CHECK(longer.status().code() == ErrorCode::bad_field);
  CHECK_THAT(longer.status().message(), Catch::Contains("varint #1 is over 4 bytes"));
}

TEST_CASE("long level payloads: runs of one-byte varints and a bad value far in, in both codings") {
  // The paper's genus-1 counts: 150 odd vertices at level 1.
  const FileContents c = test::sample_contents(50, 150, 100, 1);
  constexpr uint32_t kCount = 150;
  const auto file_of = [&](uint8_t coding_id, const std::vector<uint8_t>& raw) {
    return read_all(assemble(encode_header(c.header), std::vector<RawChunk>{{kCtrl, encode_control(ControlCodec::draco, c.control_mesh)},
                                                                            {kLevl, level_chunk(coding_id, kCount, raw)}}));
  };
  // One-byte values (zigzag: 2k -> k, 2k+1 -> -k-1), then a two-byte one last.
  std::vector<uint8_t> raw;
  std::vector<int32_t> want;
  for (uint32_t i = 0; i + 1 < kCount; ++i) {
    raw.push_back(static_cast<uint8_t>(i % 128));
    want.push_back(i % 2 ? -static_cast<int32_t>(i % 128 / 2) - 1 : static_cast<int32_t>(i % 128 / 2));
  }
  raw.push_back(0x81), raw.push_back(0x01);  // z = 129: q = -65
  want.push_back(-65);
  {
    const Reader r = file_of(1, raw);
    REQUIRE(r.complete());
    CHECK(r.level(1).q == want);
  }
  // A non-canonical varint at #20, after a run the fast path takes.
  auto bad = std::vector<uint8_t>(raw.begin(), raw.begin() + 20);
  bad.push_back(0x80), bad.push_back(0x00);
  bad.insert(bad.end(), raw.begin() + 21, raw.end());
  {
    const Reader r = file_of(1, bad);
    CHECK(r.status().code() == ErrorCode::bad_field);
    CHECK_THAT(r.status().message(), Catch::Contains("#20 "));
  }
  // Byte planes: every value valid but #137, just past 2^24.
  std::vector<uint8_t> planes(4 * kCount, 0);
  for (uint32_t i = 0; i < kCount; ++i) planes[i] = static_cast<uint8_t>(i);
  {
    const Reader r = file_of(0, planes);
    REQUIRE(r.complete());
    CHECK(r.level(1).q[137] == -69);  // z = 137
  }
  planes[137] = 2, planes[3 * kCount + 137] = 2;  // z = 2^25 + 2
  const Reader r = file_of(0, planes);
  CHECK(r.status().code() == ErrorCode::bad_field);
  CHECK_THAT(r.status().message(), Catch::Contains("#137 "));
}
