// dbss-ref FILE.dbss: decodes a file with the reference decoder and prints
// one line per level, `level L vertices V triangles T fnv1a64 HEX`, then
// `error CODE` (exit 1) if the file is invalid.
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include "reference.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: dbss-ref FILE.dbss\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::printf("error io\n");
    return 1;
  }
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const dbss_ref::Decoded decoded = dbss_ref::decode(bytes);
  for (size_t l = 0; l < decoded.levels.size(); ++l) {
    const dbss_ref::Mesh& mesh = decoded.levels[l];
    std::printf("level %zu vertices %zu triangles %zu fnv1a64 %016" PRIx64 "\n", l,
                mesh.positions.size() / 3, mesh.triangles.size() / 3, dbss_ref::fnv1a64(mesh));
  }
  if (!decoded.error.empty()) {
    std::printf("error %s\n", decoded.error.c_str());
    return 1;
  }
  return 0;
}
