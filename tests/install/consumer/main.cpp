// Links the installed dbss::decoder and dbss::io only.  With a .dbss file as
// its argument it also reads it from disk and decodes its finest level.
#include <cstdio>
#include <vector>

#include "dbss/decoder/control_mesh.h"
#include "dbss/decoder/progressive.h"
#include "dbss/format/crc32c.h"
#include "dbss/format/reader.h"
#include "dbss/io/file.h"

int main(int argc, char** argv) {
  const std::vector<uint8_t> check = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  if (dbss::format::crc32c(check) != 0xE3069283u) return 1;
  const std::vector<uint8_t> junk(64, 0x42);
  if (dbss::decode_control_mesh(junk, 100, 100).ok()) return 1;
  if (dbss::format::read_all(junk).status().code() != dbss::ErrorCode::bad_signature) return 1;
  if (argc > 1) {
    const auto bytes = dbss::io::read_file(argv[1]);
    if (!bytes.ok()) return std::fprintf(stderr, "%s\n", bytes.status().message().c_str()), 1;
    const auto mesh = dbss::decode_bytes(bytes.value());
    if (!mesh.ok() || mesh.value().triangle_count() == 0) return 1;
    std::printf("decoded %zu triangles\n", mesh.value().triangle_count());
  }
  std::puts("decoder-only consumer ok");
  return 0;
}
