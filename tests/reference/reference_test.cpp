// The reference decoder (spec/reference, written from spec/*.md alone)
// against the golden files and against the project's fast path: the
// progressive decoder, LevelRefiner and the container reader.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../shapes.h"
#include "dbss/decoder/level_refiner.h"
#include "dbss/decoder/progressive.h"
#include "project_decode.h"
#include "reference.h"

namespace {

const std::string kDir = std::string(DBSS_SOURCE_DIR) + "/tests/golden/v1/";
const char* const kGoldens[] = {"torus-4-levels", "icosahedron-4-levels", "bipyramid9-3-levels",
                                "bordered-grid-3-levels", "cube-creases-4-levels", "roof-creases-3-levels",
                                "cylinder-creases-3-levels", "torus-context-4-levels",
                                "bipyramid9-context-3-levels", "cube-creases-context-3-levels",
                                "bordered-grid-boundary-3-levels", "bipyramid9-holes-boundary-3-levels"};

std::vector<uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<uint64_t> read_hashes(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  std::vector<uint64_t> out;
  std::string word;
  while (in >> word) out.push_back(std::stoull(word, nullptr, 16));
  return out;
}

dbss_ref::Mesh to_ref(const dbss::TriangleMesh& m) { return {m.positions, m.triangles, {}, {}}; }

bool same_bits(std::span<const float> a, std::span<const float> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), 4 * a.size()) == 0;
}

}  // namespace

TEST_CASE("every golden file decodes to its recorded hashes") {
  for (const char* name : kGoldens) {
    INFO(name);
    const auto bytes = read_bytes(kDir + name + ".dbss");
    const auto expect = read_hashes(kDir + name + ".hashes");
    const dbss_ref::Decoded d = dbss_ref::decode(bytes);
    CHECK(d.error.empty());
    std::vector<uint64_t> got;
    for (const auto& level : d.levels) got.push_back(dbss_ref::fnv1a64(level));
    CHECK(got == expect);
  }
  // The spec's standard FNV-1a 64 of the icosahedron's finest level, as
  // dbss-ref prints it.
  const dbss_ref::Decoded ico = dbss_ref::decode(read_bytes(kDir + "icosahedron-4-levels.dbss"));
  REQUIRE(ico.levels.size() == 5);
  CHECK(dbss_ref::fnv1a64(ico.levels[4]) == 0x6beb481acb1acab8ull);
  // Section 5's check values.
  const uint8_t digits[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  CHECK(dbss_ref::crc32c(digits) == 0xE3069283u);
  const std::vector<uint8_t> zeros(32, 0);
  CHECK(dbss_ref::crc32c(zeros) == 0x8A9136AAu);
}

TEST_CASE("golden files give the progressive decoder's bits at every level") {
  for (const char* name : kGoldens) {
    INFO(name);
    const auto bytes = read_bytes(kDir + name + ".dbss");
    const dbss_ref::Decoded ref = dbss_ref::decode(bytes);
    const dbss::test::ProjectDecode project = dbss::test::project_decode(bytes);
    REQUIRE(ref.error.empty());
    REQUIRE(project.error.empty());
    REQUIRE(ref.levels.size() == project.levels.size());
    for (size_t l = 0; l < ref.levels.size(); ++l) {
      INFO("level " << l);
      CHECK(same_bits(ref.levels[l].positions, project.levels[l].positions));
      CHECK(ref.levels[l].triangles == project.levels[l].triangles);
    }
  }
}

namespace {

// A disk: a centre of valence n (interior, extraordinary unless n = 6) and
// a rim of boundary vertices.
dbss::TriangleMesh disk(uint32_t n) {
  dbss::TriangleMesh m;
  m.positions = {0.0f, 0.0f, 0.3f};
  for (uint32_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    m.positions.insert(m.positions.end(), {float(std::cos(a)), float(std::sin(a)), 0.0f});
  }
  for (uint32_t i = 0; i < n; ++i) m.triangles.insert(m.triangles.end(), {0, 1 + i, 1 + (i + 1) % n});
  return m;
}

std::vector<dbss::TriangleMesh> shapes() {
  using namespace dbss::test;
  return {
      jitter(torus(9, 7), 0.05f),         // closed, all regular
      jitter(icosahedron(), 0.1f),        // valence 5
      jitter(tetrahedron(), 0.1f),        // valence 3
      jitter(bipyramid(4), 0.1f),         // valence 4 (zero weights omitted)
      jitter(bipyramid(11), 0.1f, 3),     // valence 11 next to valence 4
      jitter(bipyramid(64), 0.02f, 5),    // the largest valence
      jitter(uv_sphere(6, 10), 0.05f),    // poles of valence 10
      jitter(planar_grid(6, 5), 0.1f),    // boundary, valences 4, 6 and 8
      jitter(disk(5), 0.05f),             // boundary around an extraordinary vertex
      jitter(disk(3), 0.05f, 7),          // a valence-3 centre whose every edge ends on the boundary
  };
}

}  // namespace

TEST_CASE("subdivide agrees with LevelRefiner bit for bit, with and without displacement") {
  int shape = 0;
  for (const dbss::TriangleMesh& m : shapes()) {
    INFO("shape " << shape++);
    for (int32_t amplitude : {0, 40}) {
      INFO("amplitude " << amplitude);
      auto refiner = dbss::LevelRefiner::create(m);
      REQUIRE(refiner.ok());
      dbss_ref::Mesh ref = to_ref(m);
      uint32_t seed = 99;
      for (int level = 1; level <= 3; ++level) {
        INFO("level " << level);
        const float step = 0.004f / float(level);
        // The reference's plain subdivision: the fast path's undisplaced
        // points must be these, bit for bit.
        const dbss_ref::Mesh plain = dbss_ref::subdivide(ref, {}, 0.0f);
        const size_t V = ref.positions.size() / 3;
        std::vector<int32_t> q;
        std::vector<uint8_t> points_agree(plain.positions.size() / 3 - V, 1);
        const dbss::OddChooser choose = [&](uint32_t e, const double p[3], const double*, const float*,
                                            const float*) {
          for (int c = 0; c < 3; ++c) {
            const float got = static_cast<float>(p[c]), want = plain.positions[3 * (V + e) + c];
            if (std::memcmp(&got, &want, 4) != 0 || double(got) != p[c]) points_agree[e] = 0;
          }
          if (amplitude == 0) return int32_t{0};
          const uint32_t s = (e + seed) * 2654435761u;
          return static_cast<int32_t>((s >> 8) % (2 * uint32_t(amplitude) + 1)) - amplitude;
        };
        refiner.value().refine(choose, step, q, 1);
        seed += 17;
        CHECK(std::find(points_agree.begin(), points_agree.end(), 0) == points_agree.end());
        const dbss_ref::Mesh next = dbss_ref::subdivide(ref, q, step);
        CHECK(same_bits(next.positions, refiner.value().positions()));
        CHECK(std::equal(next.triangles.begin(), next.triangles.end(), refiner.value().triangles().begin(),
                         refiner.value().triangles().end()));
        // A zero q moves nothing: equal values (a -0 may become +0).
        if (amplitude == 0)
          for (size_t i = 0; i < plain.positions.size(); ++i) REQUIRE(plain.positions[i] == next.positions[i]);
        ref = next;
      }
    }
  }
}
