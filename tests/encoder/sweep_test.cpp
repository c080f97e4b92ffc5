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

TEST_CASE("every flipped bit of a real file is caught: all but framing bytes by a checksum") {
  const auto file = encoded_example();
  const format::Reader r = format::read_all(file);
  REQUIRE(r.complete());
  // Bytes whose flips the structure checks catch before any CRC is
  // computed: the signature, and each chunk's length and type (which must
  // agree with the table of contents).  Every other flip is the CRC's.
  std::vector<bool> framing(file.size(), false), free_length(file.size(), false);
  for (size_t i = 0; i < 8; ++i) framing[i] = true;
  auto mark_frame = [&](uint64_t offset) {
    for (uint64_t i = offset; i < offset + 8; ++i) framing[i] = true;
  };
  // HEAD's and INDX's lengths are checked against a range (section 12), not
  // against the table of contents: a damaged one still in range makes the
  // reader check that many bytes' CRC.
  const uint64_t head = 8, indx = 8 + format::kChunkOverhead + format::kHeadSize;
  for (uint64_t at : {head, indx}) {
    mark_frame(at);
    for (uint64_t i = at; i < at + 4; ++i) free_length[i] = true;
  }
  for (const auto& e : r.toc()) mark_frame(e.offset);
  // The codes spec section 5 names for each kind of damage.
  const auto structural = [](ErrorCode c) {
    return c == ErrorCode::bad_structure || c == ErrorCode::truncated || c == ErrorCode::limit_exceeded;
  };
  size_t by_crc_in_length = 0;
  for (size_t i = 0; i < file.size(); ++i)
    for (int bit = 0; bit < 8; ++bit) {
      auto bad = file;
      bad[i] ^= static_cast<uint8_t>(1u << bit);
      ProgressiveDecoder d;
      d.feed(bad);
      const ErrorCode c = d.finish().code();
      INFO("byte " << i << " bit " << bit << ": " << error_code_name(c));
      if (i < 8) {
        REQUIRE(c == ErrorCode::bad_signature);
      } else if (free_length[i] && c == ErrorCode::checksum_mismatch) {
        ++by_crc_in_length;
      } else if (framing[i]) {
        REQUIRE(structural(c));
      } else {
        REQUIRE(c == ErrorCode::checksum_mismatch);
      }
    }
  // Both ways occur in those two length fields (in range: CRC; out: structure).
  CHECK(by_crc_in_length > 0);
  CHECK(by_crc_in_length < 64);
}
