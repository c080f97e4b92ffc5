// Prints a mesh file's counts and the spec's level hash of its positions
// (spec/decoding.md section 8), read through the io library: the CLI test
// checks that `dbss decode` writes the decoded level itself, bit for bit, in
// every mesh format whose text or bytes keep binary32 exactly.
#include <bit>
#include <cstdint>
#include <cstdio>

#include "dbss/io/geometry_files.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fputs("usage: mesh_hash MESH\n", stderr);
    return 1;
  }
  auto m = dbss::read_geometry(argv[1]);
  if (!m.ok()) {
    std::fprintf(stderr, "%s\n", m.status().message().c_str());
    return 1;
  }
  uint64_t h = 0xcbf29ce484222325ull;
  for (float f : m.value().points.xyz) {
    const uint32_t bits = std::bit_cast<uint32_t>(f);
    for (int k = 0; k < 4; ++k) h = (h ^ ((bits >> (8 * k)) & 0xFF)) * 0x100000001b3ull;
  }
  std::printf("vertices %zu triangles %zu fnv1a64 %016llx\n", m.value().points.size(), m.value().triangles.size() / 3,
              static_cast<unsigned long long>(h));
  return 0;
}
