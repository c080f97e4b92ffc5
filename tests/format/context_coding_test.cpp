// LEVL coding 2 (spec/dbss-format.md section 9b): round trips over value
// distributions that reach every branch of the binarization, the version
// rule, and hostile streams (truncated, cut, extended, flipped) that must
// give the section's codes without a crash.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <string>

#include "dbss/format/reader.h"
#include "dbss/format/writer.h"
#include "samples.h"

using namespace dbss;
using namespace dbss::format;

namespace {

FileContents context_contents(uint32_t seed, int32_t spread) {
  FileContents c = test::sample_contents(50, 150, 100, 3, seed);
  c.header.version_minor = kContextCodingVersionMinor;
  std::mt19937 rng(seed);
  for (auto& level : c.levels) {
    level.coding = DisplacementCoding::context;
    // Mostly zeros and small values, as a real level has, with runs and a
    // few values in the Exp-Golomb tail.
    std::geometric_distribution<int32_t> small(0.6);
    for (auto& q : level.q) {
      const uint32_t r = rng() % 100;
      q = r < 40 ? 0 : r < 97 ? small(rng) : static_cast<int32_t>(rng() % (2 * spread + 1)) - spread;
      if (rng() & 1) q = -q;
    }
  }
  // The extremes and the unary/Exp-Golomb border of section 9b.
  auto& q = c.levels[2].q;
  q[0] = kMaxAbsDisplacement, q[1] = -kMaxAbsDisplacement, q[2] = 14, q[3] = 15, q[4] = -16, q[5] = 29, q[6] = 30;
  return c;
}

// The LEVL chunk of `level` (1-based) inside `file`.
TocEntry level_entry(const std::vector<TocEntry>& toc, uint32_t level) {
  uint32_t seen = 0;
  for (const TocEntry& e : toc)
    if (e.type == kLevl && ++seen == level) return e;
  FAIL("no such level");
  return {};
}

// Rewrites LEVL `level`'s stream to `stream` (raw_size and the chunk
// length follow it), keeping every other chunk's bytes.
std::vector<uint8_t> with_stream(const FileContents& c, uint32_t level, const std::vector<uint8_t>& stream,
                                 uint32_t raw_size_change = 0) {
  std::vector<RawChunk> body;
  body.push_back({kCtrl, encode_control(c.control_codec, c.control_mesh)});
  for (const Level& l : c.levels) {
    std::vector<uint8_t> d = encode_level(l, 19).value();
    if (l.index == level) {
      d.resize(16);
      const auto n = static_cast<uint32_t>(stream.size()) + raw_size_change;
      for (int k = 0; k < 4; ++k) d[12 + k] = static_cast<uint8_t>(n >> (8 * k));
      d.insert(d.end(), stream.begin(), stream.end());
    }
    body.push_back({kLevl, std::move(d)});
  }
  return assemble(encode_header(c.header), body);
}

}  // namespace

TEST_CASE("context coding round-trips every branch of its binarization and keeps the version rule") {
  for (uint32_t seed : {1u, 2u, 3u}) {
    for (int32_t spread : {20, 5000, kMaxAbsDisplacement}) {
      const FileContents c = context_contents(seed, spread);
      auto bytes = serialize(c);
      REQUIRE(bytes.ok());
      const Reader r = read_all(bytes.value());
      INFO("seed " << seed << " spread " << spread << ": " << r.status().to_string());
      REQUIRE(r.complete());
      CHECK(r.header().version_minor == 2);
      for (uint32_t l = 1; l <= 3; ++l) CHECK(r.level(l) == c.levels[l - 1]);
    }
  }
  // All zeros: a few bytes for thousands of values.
  FileContents zeros = context_contents(4, 10);
  for (auto& q : zeros.levels[2].q) q = 0;
  const auto chunk = encode_level(zeros.levels[2], 19).value();
  CHECK(chunk.size() < 16 + 32);
  CHECK(read_all(serialize(zeros).value()).level(3) == zeros.levels[2]);

  // A writer does not put coding 2 in a file that says 1.1, and the lowest
  // version that holds the contents is 1.2.
  FileContents old = context_contents(5, 10);
  CHECK(minimum_version_minor(old) == 2);
  old.header.version_minor = kCreaseVersionMinor;
  CHECK(serialize(old).status().code() == ErrorCode::invalid_argument);
}

TEST_CASE("a 1.1 file with a coding-2 level is rejected as an unknown coding") {
  FileContents c = context_contents(6, 50);
  // The same bytes marked 1.1: what a 1.1 reader sees in a 1.2 file.
  c.header.version_minor = 1;
  std::vector<RawChunk> body;
  body.push_back({kCtrl, encode_control(c.control_codec, c.control_mesh)});
  for (const Level& l : c.levels) body.push_back({kLevl, encode_level(l, 19).value()});
  const std::vector<uint8_t> marked = assemble(encode_header(c.header), body);
  const Reader r = read_all(marked);
  CHECK(r.status().code() == ErrorCode::bad_field);
  CHECK(r.levels_ready() == 0);
  CHECK(r.status().offset() == level_entry(r.toc(), 1).offset + 8 + 1);  // the coding byte
}

TEST_CASE("hostile coding-2 streams give the spec's codes when cut or extended or flipped") {
  const FileContents c = context_contents(7, 300);
  const auto good = encode_level(c.levels[1], 19).value();
  const std::vector<uint8_t> stream(good.begin() + 16, good.end());
  // The chunks before LEVL 2 are the same in every variant below.
  const auto toc = read_all(with_stream(c, 2, stream)).toc();
  const uint64_t stream_at = level_entry(toc, 2).offset + 8 + 16;

  // Every cut: the stream ends before its last value needs a byte, or it
  // is under 4 bytes (raw_size's range).
  for (size_t n = 0; n < stream.size(); ++n) {
    const std::vector<uint8_t> cut(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(n));
    const Reader r = read_all(with_stream(c, 2, cut));
    INFO("cut to " << n << ": " << r.status().to_string());
    CHECK(r.levels_ready() == 1);
    if (n < 4) {
      CHECK(r.status().code() == ErrorCode::bad_field);
    } else {
      CHECK(r.status().code() == ErrorCode::compression);
      CHECK(r.status().offset() == stream_at + n);
    }
  }
  // A byte too many: left over after the last value.
  std::vector<uint8_t> longer = stream;
  longer.push_back(0);
  const Reader extra = read_all(with_stream(c, 2, longer));
  CHECK(extra.status().code() == ErrorCode::compression);
  CHECK(extra.status().offset() == stream_at + stream.size());
  CHECK(extra.levels_ready() == 1);

  // Any flipped bit: an error of section 9b or other values, never a crash;
  // level 1 stays usable either way.
  size_t failed = 0;
  for (size_t i = 0; i < stream.size(); ++i) {
    for (int bit = 0; bit < 8; bit += 3) {
      std::vector<uint8_t> bad = stream;
      bad[i] ^= static_cast<uint8_t>(1u << bit);
      const Reader r = read_all(with_stream(c, 2, bad));
      CHECK(r.levels_ready() >= 1);
      if (!r.status().ok()) {
        ++failed;
        const ErrorCode code = r.status().code();
        CHECK((code == ErrorCode::compression || code == ErrorCode::bad_field));
      }
    }
  }
  CHECK(failed > 0);

  // All 0xFF: Exp-Golomb prefixes run to their limit (bad_field), or the
  // stream ends first (compression).
  const Reader ff = read_all(with_stream(c, 2, std::vector<uint8_t>(64, 0xFF)));
  CHECK((ff.status().code() == ErrorCode::bad_field || ff.status().code() == ErrorCode::compression));
  // raw_size not the stream's size (check 7).
  for (uint32_t change : {1u, ~0u}) {
    const Reader r = read_all(with_stream(c, 2, stream, change));
    CHECK(r.status().code() == ErrorCode::bad_field);
    CHECK(r.status().offset() == level_entry(toc, 2).offset + 8 + 12);
  }
}

TEST_CASE("context coding gives the spec's example streams") {
  // dbss-format.md section 9b, "Examples".
  Level level;
  level.index = 1;
  level.step = 1;
  level.coding = DisplacementCoding::context;
  level.q = {0, 1, -1, 20, 0, 0, -3, kMaxAbsDisplacement};
  const std::vector<uint8_t> first = {0x4f, 0x13, 0xbd, 0xa6, 0xd9, 0xa8, 0x05, 0xff,
                                      0xff, 0xdf, 0xff, 0xfc, 0x80, 0x00, 0x00, 0x00};
  auto d = encode_level(level, 19).value();
  CHECK(std::vector<uint8_t>(d.begin() + 16, d.end()) == first);
  level.q.assign(1000, 0);
  d = encode_level(level, 19).value();
  CHECK(std::vector<uint8_t>(d.begin() + 16, d.end()) == std::vector<uint8_t>(7, 0));
}

// The decoder takes runs of zeros in context 0 through a loop of its own
// (Decoder::zeros): runs of every length from 1 to hundreds, a level that
// starts and one that ends inside a run, values right after a run, and cuts
// that end a stream inside a run, which must name the displacement the
// general path would (the index never goes back as the cut grows).
TEST_CASE("coding-2 runs of zeros round-trip and report cuts inside a run") {
  for (uint32_t seed : {11u, 12u, 13u}) {
    FileContents c = context_contents(seed, 40);
    std::mt19937 rng(seed);
    for (auto& level : c.levels) {
      size_t i = 0;
      while (i < level.q.size()) {
        const size_t run = std::min<size_t>(level.q.size() - i, 1 + rng() % (rng() % 4 == 0 ? 400 : 12));
        for (size_t k = 0; k < run; ++k) level.q[i++] = 0;
        for (uint32_t k = rng() % 3; k > 0 && i < level.q.size(); --k)
          level.q[i++] = static_cast<int32_t>(rng() % 61) - 30;
      }
    }
    c.levels[0].q.back() = 0;   // ends inside a run
    c.levels[1].q.front() = 7;  // starts with a value
    const Reader r = read_all(serialize(c).value());
    INFO("seed " << seed << ": " << r.status().to_string());
    REQUIRE(r.complete());
    for (uint32_t l = 1; l <= 3; ++l) CHECK(r.level(l) == c.levels[l - 1]);

    const auto good = encode_level(c.levels[2], 19).value();
    const std::vector<uint8_t> stream(good.begin() + 16, good.end());
    const uint64_t stream_at = level_entry(read_all(with_stream(c, 3, stream)).toc(), 3).offset + 8 + 16;
    long last_index = -1;
    for (size_t n = 4; n < stream.size(); ++n) {
      const std::vector<uint8_t> cut(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(n));
      const Reader rc = read_all(with_stream(c, 3, cut));
      INFO("cut to " << n << ": " << rc.status().to_string());
      CHECK(rc.levels_ready() == 2);
      CHECK(rc.status().code() == ErrorCode::compression);
      CHECK(rc.status().offset() == stream_at + n);
      const std::string& m = rc.status().message();
      const size_t hash = m.find('#');
      REQUIRE(hash != std::string::npos);
      const long index = std::stol(m.substr(hash + 1));
      CHECK(index >= last_index);
      CHECK(index < static_cast<long>(c.levels[2].q.size()));
      last_index = index;
    }
  }
}
