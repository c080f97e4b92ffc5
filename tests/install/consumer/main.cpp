#include <cstdio>
#include <vector>

#include "dbss/decoder/control_mesh.h"
#include "dbss/format/crc32c.h"
#include "dbss/format/reader.h"

int main() {
  const std::vector<uint8_t> check = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  if (dbss::format::crc32c(check) != 0xE3069283u) return 1;
  const std::vector<uint8_t> junk(64, 0x42);
  if (dbss::decode_control_mesh(junk, 100, 100).ok()) return 1;
  if (dbss::format::read_all(junk).status().code() != dbss::ErrorCode::bad_signature) return 1;
  std::puts("decoder-only consumer ok");
  return 0;
}
