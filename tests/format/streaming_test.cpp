#include <catch2/catch.hpp>

#include <random>

#include "samples.h"

using namespace dbss;
using namespace dbss::format;

namespace {
// Feeds `file` in pieces of `piece` bytes; after every piece, what is ready
// must be exactly what the bytes so far contain.
Reader feed_in_pieces(const test::SampleFile& sample, size_t piece) {
  const std::vector<uint8_t>& file = sample.bytes;
  Reader r;
  uint32_t last_levels = 0;
  for (size_t at = 0; at < file.size(); at += piece) {
    const size_t n = std::min(piece, file.size() - at);
    REQUIRE(r.feed(std::span<const uint8_t>(file.data() + at, n)).ok());
    REQUIRE(r.levels_ready() >= last_levels);
    last_levels = r.levels_ready();
    REQUIRE(r.levels_ready() == test::levels_within(sample, at + n));
    REQUIRE(r.has_control() == test::ends_within(sample, kCtrl, at + n));
    REQUIRE(r.offset() == at + n);
  }
  REQUIRE(r.finish().ok());
  return r;
}

void check_equal(const Reader& a, const Reader& b) {
  REQUIRE(a.complete());
  REQUIRE(b.complete());
  CHECK(a.header() == b.header());
  CHECK(a.toc() == b.toc());
  REQUIRE(a.levels_ready() == b.levels_ready());
  for (uint32_t l = 1; l <= a.levels_ready(); ++l) CHECK(a.level(l) == b.level(l));
  CHECK(a.metadata() == b.metadata());
  CHECK(std::equal(a.control_payload().begin(), a.control_payload().end(), b.control_payload().begin(),
                   b.control_payload().end()));
}
}  // namespace

TEST_CASE("every piece size from 1 byte to the whole file gives the same result") {
  const auto sample = test::small_sample();
  const auto& file = sample.bytes;
  const Reader whole = read_all(file);
  REQUIRE(whole.complete());
  CHECK(whole.toc() == sample.toc);  // the reader finds what the writer wrote
  for (size_t piece = 1; piece <= file.size(); ++piece) {
    INFO("piece size " << piece);
    check_equal(feed_in_pieces(sample, piece), whole);
  }
}

TEST_CASE("a larger file in small, prime and random piece sizes") {
  const auto sample = test::big_sample();
  const auto& file = sample.bytes;
  const Reader whole = read_all(file);
  for (size_t piece : {1u, 2u, 3u, 7u, 13u, 64u, 251u, 1460u, 4096u}) {
    INFO("piece size " << piece);
    check_equal(feed_in_pieces(sample, piece), whole);
  }
  std::mt19937 rng(11);
  for (int round = 0; round < 20; ++round) {
    Reader r;
    for (size_t at = 0; at < file.size();) {
      const size_t n = std::min<size_t>(1 + rng() % 300, file.size() - at);
      REQUIRE(r.feed(std::span<const uint8_t>(file.data() + at, n)).ok());
      at += n;
    }
    REQUIRE(r.finish().ok());
    check_equal(r, whole);
  }
}
