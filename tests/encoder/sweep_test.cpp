// Sweeps over a real encoder output: every truncation decodes exactly the
// complete levels (bit for bit as the whole file does), every bit flip is
// refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>

#include "dbss/decoder/progressive.h"
#include "dbss/encoder/encode.h"
#include "dbss/format/reader.h"

using namespace dbss;

namespace {
// The shipped example through the whole encoder, as `dbss encode` writes it.
std::vector<uint8_t> encoded_example() {
  auto pc = read_points(std::string(DBSS_SOURCE_DIR) + "/examples/double-torus.xyz");
  REQUIRE(pc.ok());
  EncodeOptions o;
  o.levels = 2;
  o.source_name = "double-torus.xyz";
  auto e = encode_points(pc.value(), o);
  REQUIRE(e.ok());
  return e.value().bytes;
}
}  // namespace

TEST_CASE("a real file cut at every offset decodes its complete levels exactly as the whole file") {
  const auto file = encoded_example();
  std::vector<std::vector<float>> whole;
  {
    ProgressiveDecoder d;
    REQUIRE(d.feed(file).ok());
    REQUIRE(d.finish().ok());
    for (uint32_t l = 0; l <= 2; ++l) whole.push_back(d.decode(l).value().copy().positions);
  }
  const format::Reader r = format::read_all(file);
  for (size_t n = 0; n < file.size(); ++n) {
    ProgressiveDecoder d;
    d.feed({file.data(), n});
    REQUIRE(d.finish().code() == ErrorCode::truncated);
    int expect = -1;
    for (const auto& e : r.toc())
      if (e.end() <= n && (e.type == format::kCtrl || e.type == format::kLevl)) ++expect;
    REQUIRE(d.ready_level() == expect);
    if (expect >= 0) {
      auto m = d.decode(static_cast<uint32_t>(expect));
      REQUIRE(m.ok());
      REQUIRE(m.value().positions.size() == whole[expect].size());
      REQUIRE(std::memcmp(m.value().positions.data(), whole[expect].data(), whole[expect].size() * 4) == 0);
    }
  }
}

TEST_CASE("every flipped bit of a real file is caught; all but framing bytes by a checksum") {
  const auto file = encoded_example();
  const format::Reader r = format::read_all(file);
  REQUIRE(r.complete());
  // Bytes whose flips the structure checks catch before any CRC is
  // computed: the signature, and each chunk's length and type (which must
  // agree with the table of contents).  Every other flip is the CRC's.
  std::vector<bool> framing(file.size(), false);
  for (size_t i = 0; i < 8; ++i) framing[i] = true;
  auto mark_frame = [&](uint64_t offset) {
    for (uint64_t i = offset; i < offset + 8; ++i) framing[i] = true;
  };
  mark_frame(8);                                              // HEAD
  mark_frame(8 + format::kChunkOverhead + format::kHeadSize);  // INDX
  for (const auto& e : r.toc()) mark_frame(e.offset);
  size_t flips = 0, by_structure = 0;
  for (size_t i = 0; i < file.size(); ++i)
    for (int bit = 0; bit < 8; ++bit) {
      auto bad = file;
      bad[i] ^= static_cast<uint8_t>(1u << bit);
      ProgressiveDecoder d;
      d.feed(bad);
      const Status s = d.finish();
      INFO("byte " << i << " bit " << bit << ": " << s.to_string());
      REQUIRE(!s.ok());
      ++flips;
      if (s.code() != ErrorCode::checksum_mismatch) {
        REQUIRE(framing[i]);
        ++by_structure;
      }
    }
  CHECK(flips == 8 * file.size());
  CHECK(by_structure <= 8 * size_t(std::count(framing.begin(), framing.end(), true)));
}
