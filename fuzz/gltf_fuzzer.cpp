// libFuzzer target: glTF reading (io's parse_geometry on .glb and .gltf
// bytes: tinygltf's parser, then dbss's accessor, index and node checks).
//
// The first input byte picks the name: bit 0 set reads the rest as
// "fuzz.glb", else as "fuzz.gltf".  The name sits in a directory that does
// not exist, so a .gltf's external buffers never reach the file system.
// Oracles (always on): a file read without error has whole triangles, every
// index names a vertex, and every coordinate is finite.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "dbss/io/geometry_files.h"

namespace {
void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "gltf_fuzzer: oracle failed: %s\n", what);
    std::abort();
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string name = (data[0] & 1) ? "/nonexistent-dbss-fuzz/fuzz.glb" : "/nonexistent-dbss-fuzz/fuzz.gltf";
  auto g = dbss::parse_geometry(name, std::string_view(reinterpret_cast<const char*>(data + 1), size - 1));
  if (!g.ok()) {
    check(g.status().message().rfind(name + ": ", 0) == 0, "the error names the file");
    return 0;
  }
  const dbss::GeometryFile& f = g.value();
  check(f.points.xyz.size() % 3 == 0, "whole points");
  check(f.triangles.size() % 3 == 0, "whole triangles");
  for (uint32_t i : f.triangles) check(i < f.points.size(), "indices name vertices");
  for (float x : f.points.xyz) check(std::isfinite(x), "finite coordinates");
  return 0;
}
