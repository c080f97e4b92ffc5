#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "samples.h"

using namespace dbss;
using namespace dbss::format;

namespace {
void check_same(const Reader& r, const FileContents& c) {
  REQUIRE(r.complete());
  CHECK(r.header() == c.header);
  CHECK(r.control_codec() == c.control_codec);
  CHECK(std::vector<uint8_t>(r.control_payload().begin(), r.control_payload().end()) == c.control_mesh);
  REQUIRE(r.levels_ready() == c.levels.size());
  for (uint32_t l = 1; l <= r.levels_ready(); ++l) CHECK(r.level(l) == c.levels[l - 1]);
  CHECK(r.metadata() == c.metadata);
}
}  // namespace

TEST_CASE("every chunk kind round-trips: header, control, levels in both codings, metadata") {
  for (uint8_t levels : {0, 1, 3, 5}) {
    const FileContents c = test::sample_contents(50, 150, 100, levels, levels + 3u);
    auto bytes = serialize(c);
    REQUIRE(bytes.ok());
    const Reader r = read_all(bytes.value());
    INFO("levels " << int(levels) << ": " << r.status().to_string());
    check_same(r, c);
    CHECK(r.ancillary_skipped() == 0);
  }
  // All varint, all byte planes, and no metadata.
  for (auto coding : {DisplacementCoding::varint, DisplacementCoding::byte_planes}) {
    FileContents c = test::sample_contents(4, 6, 4, 4);
    for (auto& l : c.levels) l.coding = coding;
    c.metadata.clear();
    const Reader r = read_all(serialize(c).value());
    check_same(r, c);
  }
}

TEST_CASE("zigzag maps small magnitudes to small codes and round-trips the valid range") {
  CHECK(zigzag_encode(0) == 0);
  CHECK(zigzag_encode(-1) == 1);
  CHECK(zigzag_encode(1) == 2);
  CHECK(zigzag_encode(-3) == 5);
  CHECK(zigzag_encode(200) == 400);
  CHECK(zigzag_encode(kMaxAbsDisplacement) == 1u << 25);
  for (int32_t v : {0, 1, -1, 12345, -12345, kMaxAbsDisplacement, -kMaxAbsDisplacement,
                    std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::min()})
    CHECK(zigzag_decode(zigzag_encode(v)) == v);
}

TEST_CASE("the table of contents is contiguous and a prefix up to level l gives exactly levels 0..l") {
  const auto file = test::big_file();
  const Reader whole = read_all(file);
  REQUIRE(whole.complete());
  CHECK(whole.file_size() == file.size());
  uint64_t at = 8 + kChunkOverhead + kHeadSize + kChunkOverhead + 16 + 16 * whole.toc().size();
  for (const TocEntry& e : whole.toc()) {
    CHECK(e.offset == at);
    at = e.end();
  }
  CHECK(at == file.size());
  uint32_t l = 0;
  for (const TocEntry& e : whole.toc()) {
    if (!(e.type == kLevl)) continue;
    ++l;
    Reader r;
    REQUIRE(r.feed(std::span<const uint8_t>(file.data(), e.end())).ok());
    CHECK(r.levels_ready() == l);
    for (uint32_t k = 1; k <= l; ++k) CHECK(r.level(k) == whole.level(k));
    const Status s = r.finish();
    if (e.end() == file.size()) CHECK(s.ok());
    else CHECK(s.code() == ErrorCode::truncated);
  }
  CHECK(l == 3);
}

TEST_CASE("serialize refuses contents the format cannot hold") {
  auto expect_invalid = [](FileContents c, const char* what) {
    INFO(what);
    CHECK(serialize(c).status().code() == ErrorCode::invalid_argument);
  };
  const FileContents good = test::sample_contents(50, 150, 100, 2);
  REQUIRE(serialize(good).ok());
  FileContents c = good;
  c.header.level_count = 3;
  expect_invalid(c, "level_count disagrees with the levels");
  c = good;
  c.levels[1].q.pop_back();
  expect_invalid(c, "wrong odd count");
  for (float step : {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    c = good;
    c.levels[0].step = step;
    expect_invalid(c, "bad step");
  }
  c = good;
  c.levels[0].q[5] = kMaxAbsDisplacement + 1;
  expect_invalid(c, "q over 2^24");
  c = good;
  c.control_mesh.clear();
  expect_invalid(c, "empty control mesh");
  c = good;
  c.metadata.push_back({"", "x"});
  expect_invalid(c, "empty metadata key");
  c = good;
  c.header.control_edge_count = 400;
  expect_invalid(c, "impossible edge count");
  c = good;
  c.header.bbox_min[0] = 5;
  expect_invalid(c, "inverted bounding box");
  c = good;
  c.header.flags = 1;
  expect_invalid(c, "undefined flag");
  c = good;
  c.levels[0].index = 2;
  expect_invalid(c, "levels out of order");
}
