// What spec/decoding.md publishes, recomputed: the test vector's bytes and
// level hashes (section 8) and the butterfly weights (section 5.3).  The
// values are parsed from the .md file, so the spec and the code cannot drift
// apart.  Also the streaming rule of spec/dbss-format.md section 11 on the
// test vector: damage after a level voids nothing verified before it.
#include <catch2/catch.hpp>

#include <bit>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "butterfly.h"
#include "dbss/decoder/progressive.h"
#include "dbss/format/crc32c.h"
#include "dbss/format/reader.h"
#include "dbss/io/file.h"

using namespace dbss;

namespace {

const std::string kSpec = std::string(DBSS_SOURCE_DIR) + "/spec/";

std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The body of the fenced block that opens with "```name".
std::string fenced(const std::string& md, const std::string& name) {
  const std::string open = "```" + name + "\n";
  const size_t b = md.find(open);
  REQUIRE(b != std::string::npos);
  const size_t e = md.find("```", b + open.size());
  REQUIRE(e != std::string::npos);
  return md.substr(b + open.size(), e - b - open.size());
}

// Section 8's hash, standard FNV-1a 64.
uint64_t level_hash(std::span<const float> p) {
  uint64_t h = 0xCBF29CE484222325ull;
  for (float f : p)
    for (int k = 0; k < 4; ++k) h = (h ^ ((std::bit_cast<uint32_t>(f) >> (8 * k)) & 0xFF)) * 0x100000001B3ull;
  return h;
}

// "level L vertices V triangles T fnv1a64 HEX" lines of every level.
std::string hash_lines(const std::vector<uint8_t>& file, bool expect_ok = true) {
  ProgressiveDecoder d;
  d.feed(file);
  CHECK(d.finish().ok() == expect_ok);
  std::string out;
  for (int l = 0; l <= d.ready_level(); ++l) {
    auto v = d.decode(static_cast<uint32_t>(l));
    REQUIRE(v.ok());
    char line[128];
    std::snprintf(line, sizeof line, "level %d vertices %zu triangles %zu fnv1a64 %016llx\n", l,
                  v.value().vertex_count(), v.value().triangle_count(),
                  static_cast<unsigned long long>(level_hash(v.value().positions)));
    out += line;
  }
  return out;
}

std::vector<uint8_t> test_vector() {
  auto f = io::read_file(kSpec + "test-vector/open-bipyramid-2-levels.dbss");
  REQUIRE(f.ok());
  return f.value();
}

}  // namespace

TEST_CASE("spec test vector: the hex dump is the file and it decodes to the published hashes") {
  const std::string md = text_of(kSpec + "decoding.md");
  const auto file = test_vector();
  std::vector<uint8_t> dumped;
  std::istringstream dump(fenced(md, "hexdump"));
  std::string line;
  while (std::getline(dump, line)) {
    INFO(line);
    REQUIRE(line.size() > 10);
    REQUIRE(std::stoul(line.substr(0, 8), nullptr, 16) == dumped.size());
    std::istringstream bytes(line.substr(10));
    std::string b;
    while (bytes >> b) dumped.push_back(static_cast<uint8_t>(std::stoul(b, nullptr, 16)));
  }
  CHECK(dumped == file);
  CHECK(hash_lines(file) == fenced(md, "hashes"));
  // The section 8 check values.
  CHECK(level_hash({}) == 0xcbf29ce484222325ull);
  const float one = 1.0f;
  CHECK(level_hash({&one, 1}) == 0x4b72477f9c5c2f98ull);
}

TEST_CASE("spec 5.3: the published weight bits and table hash are butterfly_weight's") {
  const std::string md = text_of(kSpec + "decoding.md");
  const std::regex row(R"(\| (\d+) \| (\d+) \| `([0-9a-f]{16})` \|)");
  size_t rows = 0;
  for (std::sregex_iterator it(md.begin(), md.end(), row), end; it != end; ++it, ++rows) {
    const uint32_t k = std::stoul((*it)[1]), j = std::stoul((*it)[2]);
    INFO("k " << k << " j " << j);
    CHECK(std::bit_cast<uint64_t>(butterfly_weight(k, j)) == std::stoull((*it)[3], nullptr, 16));
  }
  CHECK(rows == 3 + 4 + 5 + 7 + 8);
  std::smatch m;
  REQUIRE(std::regex_search(md, m, std::regex(R"(weights-fnv1a64: ([0-9a-f]{16}))")));
  uint64_t h = 0xCBF29CE484222325ull;  // FNV's standard basis here
  for (uint32_t k = 3; k <= kMaxValence; ++k) {
    if (k == 6) continue;
    for (uint32_t j = 0; j < k; ++j) {
      const uint64_t bits = std::bit_cast<uint64_t>(butterfly_weight(k, j));
      for (int i = 0; i < 8; ++i) h = (h ^ ((bits >> (8 * i)) & 0xFF)) * 0x100000001B3ull;
    }
  }
  CHECK(h == std::stoull(m[1].str(), nullptr, 16));
}

TEST_CASE("spec 11: a damaged trailing meta chunk voids no level verified before it") {
  const auto good = test_vector();
  const format::Reader r = format::read_all(good);
  REQUIRE(r.complete());
  const auto& meta = r.toc().back();
  REQUIRE(meta.type == format::kMeta);
  auto damaged = good;
  damaged[meta.offset + 12] ^= 0x20;  // a byte of its data: the CRC no longer holds
  ProgressiveDecoder d;
  CHECK(d.feed(damaged).code() == ErrorCode::checksum_mismatch);
  CHECK(d.status().code() == ErrorCode::checksum_mismatch);
  CHECK(d.ready_level() == 2);
  // The same bits as from the intact file.
  CHECK(hash_lines(damaged, false) == hash_lines(good));
  // Trailing bytes after a complete file: the same.
  auto longer = good;
  longer.push_back(0);
  CHECK(hash_lines(longer, false) == hash_lines(good));
}

TEST_CASE("tests/format/data/garbage-control.dbss: a valid container whose control mesh does not decode") {
  // The cli test runs `dbss info` on it: info must fail where decode does.
  auto f = io::read_file(std::string(DBSS_SOURCE_DIR) + "/tests/format/data/garbage-control.dbss");
  REQUIRE(f.ok());
  CHECK(format::read_all(f.value()).complete());
  ProgressiveDecoder d;
  d.feed(f.value());
  CHECK(d.finish().ok());
  CHECK(d.ready_level() == 1);
  CHECK(d.decode(0).status().code() == ErrorCode::compression);
}
