// The error code of each hand-made invalid file that spec sections 9, 10 and
// 12 settle (one check, one code, in a fixed order), so that any two
// conforming readers agree on it.
#include <catch2/catch.hpp>

#include <zstd.h>

#include <cstring>
#include <limits>

#include "samples.h"

using namespace dbss;
using namespace dbss::format;

namespace {

// A one-level file (tetrahedron counts) with its LEVL data given, so each
// test edits just the field it is about.
struct OneLevel {
  FileContents c = test::sample_contents(4, 6, 4, 1);
  std::vector<uint8_t> level = encode_level(c.levels[0], 3).value();
  Reader read(const std::vector<uint8_t>& levl, const Limits& limits = {}) const {
    const std::vector<RawChunk> body = {{kCtrl, encode_control(ControlCodec::draco, c.control_mesh)}, {kLevl, levl}};
    return read_all(assemble(encode_header(c.header), body), limits);
  }
  ErrorCode code(const std::vector<uint8_t>& levl) const { return read(levl).status().code(); }
};

std::vector<uint8_t> zstd(const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> z(ZSTD_compressBound(raw.size()));
  z.resize(ZSTD_compress(z.data(), z.size(), raw.data(), raw.size(), 1));
  return z;
}

}  // namespace

TEST_CASE("spec 9: a zstd frame declaring a size other than raw_size is a compression error") {
  OneLevel f;
  REQUIRE(f.read(f.level).complete());
  // Varint coding allows raw_size from odd_count to 4 * odd_count: the field
  // stays valid, only the frame disagrees with it.
  FileContents v = f.c;
  v.levels[0].coding = DisplacementCoding::varint;
  v.levels[0].q.assign(v.levels[0].q.size(), 1);  // one byte each
  auto data = encode_level(v.levels[0], 3).value();
  std::vector<uint8_t> raw(v.levels[0].q.size() + 1, 2);  // one byte more than raw_size
  data.resize(16);
  const auto z = zstd(raw);
  REQUIRE(ZSTD_getFrameContentSize(z.data(), z.size()) == raw.size());
  data.insert(data.end(), z.begin(), z.end());
  CHECK(f.code(data) == ErrorCode::compression);
}

TEST_CASE("spec 9: each LEVL check has one code, in order") {
  OneLevel f;
  auto edit = [&](size_t at, uint8_t byte) {
    auto d = f.level;
    d[at] = byte;
    return f.code(d);
  };
  // Too short for the 16 bytes of fields.
  CHECK(f.code(std::vector<uint8_t>(f.level.begin(), f.level.begin() + 15)) == ErrorCode::bad_field);
  CHECK(f.code({}) == ErrorCode::bad_field);
  // All fields, no frame: the empty frame is the zstd payload's problem.
  CHECK(f.code(std::vector<uint8_t>(f.level.begin(), f.level.begin() + 16)) == ErrorCode::compression);
  // level not its position: a structure error, checked before the others.
  CHECK(edit(0, 2) == ErrorCode::bad_structure);
  auto both = f.level;
  both[0] = 2, both[1] = 9, both[4] ^= 1;  // and a bad coding and odd_count
  CHECK(f.code(both) == ErrorCode::bad_structure);
  CHECK(edit(1, 2) == ErrorCode::bad_field);   // coding
  CHECK(edit(2, 1) == ErrorCode::bad_field);   // reserved
  CHECK(edit(4, 7) == ErrorCode::bad_field);   // odd_count
  CHECK(edit(11, 0xFF) == ErrorCode::bad_field);  // step: NaN
  CHECK(edit(12, 5) == ErrorCode::bad_field);  // raw_size for byte planes
  CHECK(edit(16, 0) == ErrorCode::compression);  // zstd magic
  // A value out of range in a valid frame.
  auto bad_q = f.c.levels[0];
  bad_q.q[0] = kMaxAbsDisplacement;
  auto d = encode_level(bad_q, 3).value();
  std::vector<uint8_t> raw(16 + 4 * bad_q.q.size());
  const size_t got = ZSTD_decompress(raw.data(), raw.size(), d.data() + 16, d.size() - 16);
  REQUIRE(got == 4 * bad_q.q.size());
  raw.resize(got);
  raw[3 * bad_q.q.size()] = 0x10;  // z = 2^28: high byte of value 0
  d.resize(16);
  const auto z = zstd(raw);
  d.insert(d.end(), z.begin(), z.end());
  CHECK(f.code(d) == ErrorCode::bad_field);
}

TEST_CASE("spec 12: HEAD checks the version, then its length, then its fields and 2^62, then the limits") {
  const FileContents c = test::sample_contents(4, 6, 4, 1);
  const std::vector<RawChunk> body = {{kCtrl, encode_control(ControlCodec::draco, c.control_mesh)},
                                      {kLevl, encode_level(c.levels[0], 3).value()}};
  auto code = [&](Header h, size_t extra = 0, const Limits& limits = {}) {
    auto head = encode_header(h);
    head.resize(head.size() + extra);
    return read_all(assemble(head, body), limits).status().code();
  };
  Header h = c.header;
  h.flags = 1;
  CHECK(code(h, 4) == ErrorCode::bad_structure);  // minor 0 with 60 bytes, whatever the fields
  h.version_major = 2;
  CHECK(code(h, 4) == ErrorCode::unsupported_version);
  // 30 levels of a tetrahedron: level 30 passes 2^62 edges.  The format's
  // rule comes before the reader's level limit (10) and vertex limit.
  h = c.header;
  h.level_count = 30;
  CHECK(code(h) == ErrorCode::bad_field);
  h.level_count = 12;  // within 2^62, over the level limit
  CHECK(code(h) == ErrorCode::limit_exceeded);
  // A bad field with a count over the vertex limit: the field.
  h.level_count = 1;
  h.bbox_min[0] = std::numeric_limits<float>::quiet_NaN();
  Limits tiny;
  tiny.max_vertices = 4;
  CHECK(code(h, 0, tiny) == ErrorCode::bad_field);
}

TEST_CASE("spec 12: INDX rules come before the reader's limits") {
  const FileContents c = test::sample_contents(4, 6, 4, 1);
  const RawChunk ctrl{kCtrl, encode_control(ControlCodec::draco, c.control_mesh)};
  const RawChunk levl{kLevl, encode_level(c.levels[0], 3).value()};
  const RawChunk big{ChunkType('b', 'i', 'g', 'x'), std::vector<uint8_t>(100)};
  Limits l;
  l.max_file_size = 10;
  l.max_ancillary_bytes = 10;
  const auto two_ctrl = assemble(encode_header(c.header), std::vector<RawChunk>{big, ctrl, ctrl, levl});
  CHECK(read_all(two_ctrl, l).status().code() == ErrorCode::bad_structure);
  const auto good = assemble(encode_header(c.header), std::vector<RawChunk>{big, ctrl, levl});
  CHECK(read_all(good, l).status().code() == ErrorCode::limit_exceeded);
  CHECK(read_all(good).complete());
}

TEST_CASE("spec 10: a malformed meta chunk is dropped with a warning and the file stays valid") {
  const FileContents c = test::sample_contents(4, 6, 4, 1);
  const RawChunk ctrl{kCtrl, encode_control(ControlCodec::draco, c.control_mesh)};
  const RawChunk levl{kLevl, encode_level(c.levels[0], 3).value()};
  const RawChunk good{kMeta, encode_metadata({{"encoder", "tests"}}).value()};
  auto read = [&](std::vector<uint8_t> meta) {
    return read_all(assemble(encode_header(c.header), std::vector<RawChunk>{ctrl, levl, good, {kMeta, meta}}));
  };
  auto with_key = [](std::string key) {
    // One entry: count 1, key length, key, value length 1, "v".  Built a
    // byte at a time (gcc 12 misreads the bounds of a range insert here).
    std::vector<uint8_t> d = {1, 0, 0, 0, static_cast<uint8_t>(key.size())};
    for (char ch : key) d.push_back(static_cast<uint8_t>(ch));
    for (uint8_t b : {uint8_t{1}, uint8_t{0}, uint8_t{0}, uint8_t{0}, uint8_t{'v'}}) d.push_back(b);
    return d;
  };
  auto extra = good.data;
  extra.push_back(0);  // bytes after the last entry
  for (const auto& meta : {extra, std::vector<uint8_t>{1, 0}, with_key("\xC0\x80"), with_key("a\xFF"),
                           with_key("\xED\xA0\x80"), with_key(std::string("a\0b", 3))}) {
    const Reader r = read(meta);
    CHECK(r.complete());
    REQUIRE(r.warnings().size() == 1);
    CHECK(r.warnings()[0].code() == ErrorCode::bad_field);
    CHECK(r.warnings()[0].offset() != Status::kNoOffset);
    CHECK(r.metadata().size() == 1);  // the good chunk's entry only
  }
  const Reader utf8 = read(with_key("h\xC3\xB6he \xF0\x9F\x99\x82"));
  CHECK(utf8.complete());
  CHECK(utf8.warnings().empty());
  CHECK(utf8.metadata().size() == 2);
  // The writer refuses what the reader would drop.
  CHECK(encode_metadata({{"a\xFF", "v"}}).status().code() == ErrorCode::invalid_argument);
}
