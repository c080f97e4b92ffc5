// Golden files: the decoder's output is part of the format, so decoded
// positions of committed files must keep the exact bits recorded here, on
// every compiler and optimisation level CI builds (gcc -O0 and -O3, clang).
//
// To regenerate after a deliberate, versioned format change:
//   build/bin/codec_tests "[.write-golden]"
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "../shapes.h"
#include "dbss/decoder/progressive.h"
#include "dbss/format/reader.h"
#include "dbss/format/writer.h"
#include "dbss/io/file.h"
#include "file_builder.h"

using namespace dbss;

namespace {

const std::string kDir = std::string(DBSS_SOURCE_DIR) + "/tests/golden/v1/";

struct Golden {
  const char* name;
  TriangleMesh mesh;
  uint8_t levels;
  int32_t amplitude;
  float step;
  double crease_degrees = 0;  // > 0: a version 1.1 file with crease tags
  bool context = false;       // every level in coding 2: a version 1.2 file
  int32_t boundary = 0;       // > 0: BDRY chunks of this amplitude, a version 1.3 file
};

// `m` without the triangles listed (a hole per triangle when they share
// no vertex but the poles).
TriangleMesh without_faces(TriangleMesh m, std::vector<uint32_t> faces) {
  std::sort(faces.rbegin(), faces.rend());
  for (uint32_t f : faces) m.triangles.erase(m.triangles.begin() + 3 * f, m.triangles.begin() + 3 * f + 3);
  return m;
}

std::vector<Golden> goldens() {
  return {
      {"torus-4-levels", test::jitter(test::torus(10, 5), 0.05f), 4, 60, 0.01f},
      {"icosahedron-4-levels", test::jitter(test::icosahedron(), 0.1f), 4, 100, 0.02f},
      {"bipyramid9-3-levels", test::jitter(test::bipyramid(9), 0.1f, 9), 3, 80, 0.02f},
      {"bordered-grid-3-levels", test::jitter(test::planar_grid(5, 4), 0.2f), 3, 50, 0.05f},
      // Version 1.1: crease edges and corners (spec/decoding.md 5.4).
      {"cube-creases-4-levels", test::cube(), 4, 40, 0.01f, 30},
      {"roof-creases-3-levels", test::roof_block(4), 3, 40, 0.01f, 30},
      {"cylinder-creases-3-levels", test::capped_cylinder(16, 3), 3, 40, 0.01f, 30},
      // Version 1.2: LEVL coding 2 (dbss-format.md section 9b); amplitude
      // 40 reaches the Exp-Golomb tail, 2 is mostly the zero flag.
      {"torus-context-4-levels", test::jitter(test::torus(10, 5), 0.05f), 4, 40, 0.01f, 0, true},
      {"bipyramid9-context-3-levels", test::jitter(test::bipyramid(9), 0.1f, 9), 3, 2, 0.02f, 0, true},
      {"cube-creases-context-3-levels", test::cube(), 3, 20, 0.01f, 30, true},
      // Version 1.3: BDRY chunks (dbss-format.md section 9c, decoding.md
      // 7a) on an open grid and on a bipyramid with holes, in all three
      // codings.
      {"bordered-grid-boundary-3-levels", test::jitter(test::planar_grid(5, 4), 0.2f), 3, 50, 0.05f, 0, false, 30},
      {"bipyramid9-holes-boundary-3-levels", test::jitter(without_faces(test::bipyramid(9), {0, 11}), 0.1f, 9), 3,
       40, 0.02f, 0, true, 12},
  };
}

std::vector<uint64_t> level_hashes(const std::vector<uint8_t>& file, Kernels kernels = Kernels::best) {
  std::vector<uint64_t> out;
  DecoderOptions o;
  o.kernels = kernels;
  ProgressiveDecoder d(o);
  REQUIRE(d.feed(file).ok());
  REQUIRE(d.finish().ok());
  for (int l = 0; l <= d.ready_level(); ++l) {
    auto v = d.decode(static_cast<uint32_t>(l));
    REQUIRE(v.ok());
    out.push_back(test::hash_floats(v.value().positions.data(), v.value().positions.size()));
  }
  return out;
}

}  // namespace

TEST_CASE("golden files decode to the recorded bits at every level") {
  for (const Golden& g : goldens()) {
    INFO(g.name);
    auto file = io::read_file(kDir + g.name + ".dbss");
    REQUIRE(file.ok());
    std::ifstream in(kDir + g.name + ".hashes");
    REQUIRE(in);
    std::vector<uint64_t> expect;
    std::string word;
    while (in >> word) expect.push_back(std::stoull(word, nullptr, 16));
    // Every build of the kernels: the same bits on every processor (scalar
    // and paired are the ones WebAssembly runs, without and with SIMD).
    CHECK(level_hashes(file.value(), Kernels::best) == expect);
    CHECK(level_hashes(file.value(), Kernels::baseline) == expect);
    CHECK(level_hashes(file.value(), Kernels::scalar) == expect);
    CHECK(level_hashes(file.value(), Kernels::paired) == expect);
  }
}

TEST_CASE("write golden files", "[.write-golden]") {
  for (const Golden& g : goldens()) {
    const auto bytes =
        test::build_file(g.mesh, g.levels, g.amplitude, g.step, 1, g.crease_degrees, g.context, g.boundary);
    REQUIRE(io::write_file_atomic(kDir + g.name + ".dbss", bytes).ok());
    std::ostringstream text;
    for (uint64_t h : level_hashes(bytes)) {
      char b[32];
      std::snprintf(b, sizeof b, "%016llx\n", static_cast<unsigned long long>(h));
      text << b;
    }
    const std::string s = text.str();
    REQUIRE(io::write_file_atomic(kDir + g.name + ".hashes", std::vector<uint8_t>(s.begin(), s.end())).ok());
  }
}
