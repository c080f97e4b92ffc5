#include <catch2/catch.hpp>

#include <set>

#include "samples.h"

using namespace dbss;
using namespace dbss::format;

namespace {
const std::set<ErrorCode> kExpected = {ErrorCode::bad_signature, ErrorCode::unsupported_version,
                                       ErrorCode::bad_structure, ErrorCode::checksum_mismatch,
                                       ErrorCode::unknown_critical_chunk, ErrorCode::bad_field,
                                       ErrorCode::limit_exceeded, ErrorCode::truncated,
                                       ErrorCode::trailing_data, ErrorCode::compression};

void check_flip(std::vector<uint8_t> file, size_t byte, int bit, size_t& by_checksum) {
  file[byte] ^= static_cast<uint8_t>(1u << bit);
  INFO("bit " << bit << " of byte " << byte);
  const Reader r = read_all(file);
  REQUIRE(r.failed());
  REQUIRE(kExpected.count(r.status().code()) == 1);
  REQUIRE(r.status().offset() != Status::kNoOffset);
  by_checksum += r.status().code() == ErrorCode::checksum_mismatch;
}
}  // namespace

TEST_CASE("every single-bit flip in a file is detected") {
  const auto small = test::small_file();
  size_t by_checksum = 0;
  for (size_t byte = 0; byte < small.size(); ++byte)
    for (int bit = 0; bit < 8; ++bit) check_flip(small, byte, bit, by_checksum);
  // Outside the signature and the length fields every flip is the CRC's to
  // catch; most flips must end there.
  CHECK(by_checksum > small.size() * 8 * 3 / 4);

  const auto big = test::big_file();
  by_checksum = 0;
  for (size_t byte = 0; byte < big.size(); ++byte) check_flip(big, byte, static_cast<int>(byte % 8), by_checksum);
  CHECK(by_checksum > big.size() * 3 / 4);
}

TEST_CASE("trailing bytes are refused and errors are sticky") {
  auto file = test::small_file();
  file.push_back(0);
  Reader r;
  const Status s = r.feed(file);
  CHECK(s.code() == ErrorCode::trailing_data);
  CHECK(s.offset() == file.size() - 1);
  CHECK(r.feed(file).code() == ErrorCode::trailing_data);
  CHECK(r.finish().code() == ErrorCode::trailing_data);

  Reader bad;
  std::vector<uint8_t> junk = {'P', 'K', 3, 4};
  CHECK(bad.feed(junk).code() == ErrorCode::bad_signature);
  CHECK(bad.feed(test::small_file()).code() == ErrorCode::bad_signature);
  CHECK(bad.status().offset() == 0);
}
