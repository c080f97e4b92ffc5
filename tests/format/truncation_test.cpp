#include <catch2/catch.hpp>

#include "samples.h"

using namespace dbss;
using namespace dbss::format;

TEST_CASE("a cut at every byte offset gives the complete levels so far and a truncated error") {
  for (const auto& sample : {test::small_sample(), test::big_sample()}) {
    const std::vector<uint8_t>& file = sample.bytes;
    for (size_t n = 0; n < file.size(); ++n) {
      INFO("prefix of " << n << " of " << file.size() << " bytes");
      Reader r;
      REQUIRE(r.feed(std::span<const uint8_t>(file.data(), n)).ok());
      const Status s = r.finish();
      REQUIRE(s.code() == ErrorCode::truncated);
      REQUIRE(s.offset() == n);
      REQUIRE(!s.message().empty());
      REQUIRE(r.levels_ready() == test::levels_within(sample, n));
      REQUIRE(r.has_control() == test::ends_within(sample, kCtrl, n));
      REQUIRE(r.has_header() == (n >= 8 + kChunkOverhead + kHeadSize));
      REQUIRE(!r.complete());
    }
    CHECK(read_all(file).complete());
  }
}
