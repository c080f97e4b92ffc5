#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "dbss/format/crc32c.h"

using dbss::format::crc32c;
using dbss::format::crc32c_extend;

namespace {
std::vector<uint8_t> bytes(const std::string& s) { return {s.begin(), s.end()}; }
}  // namespace

TEST_CASE("CRC-32C check values (RFC 3720)") {
  CHECK(crc32c(bytes("123456789")) == 0xE3069283u);
  CHECK(crc32c({}) == 0u);
  CHECK(crc32c(std::vector<uint8_t>(32, 0x00)) == 0x8A9136AAu);
  CHECK(crc32c(std::vector<uint8_t>(32, 0xFF)) == 0x62A8AB43u);
  std::vector<uint8_t> up(32), down(32);
  for (int i = 0; i < 32; ++i) up[i] = static_cast<uint8_t>(i), down[i] = static_cast<uint8_t>(31 - i);
  CHECK(crc32c(up) == 0x46DD794Eu);
  CHECK(crc32c(down) == 0x113FDB5Cu);
}

TEST_CASE("CRC-32C extends over any split, including the 8-byte fast path") {
  std::vector<uint8_t> data(1000);
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i * 131 + 7);
  const uint32_t whole = crc32c(data);
  for (size_t cut = 0; cut <= data.size(); cut += 37) {
    const uint32_t a = crc32c_extend(0, std::span<const uint8_t>(data.data(), cut));
    CHECK(crc32c_extend(a, std::span<const uint8_t>(data.data() + cut, data.size() - cut)) == whole);
  }
  // A bitwise reference for odd lengths and alignments.
  auto slow = [](std::span<const uint8_t> b) {
    uint32_t c = 0xFFFFFFFFu;
    for (uint8_t x : b) {
      c ^= x;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0x82F63B78u & (0u - (c & 1u)));
    }
    return ~c;
  };
  for (size_t start = 0; start < 9; ++start)
    for (size_t len : {0u, 1u, 7u, 8u, 9u, 15u, 16u, 17u, 100u}) {
      const std::span<const uint8_t> s(data.data() + start, len);
      CHECK(crc32c(s) == slow(s));
    }
}
