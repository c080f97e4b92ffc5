// LEVL coding 2 through the whole decoder: a level coded with the context
// coder gives the same meshes, bit for bit, as the same displacements coded
// the zstd ways, whole or fed in pieces, and matches the reference decoder.
#include <catch2/catch.hpp>

#include <algorithm>

#include "../shapes.h"
#include "dbss/decoder/progressive.h"
#include "dbss/format/reader.h"
#include "file_builder.h"
#include "levl_context.h"
#include "reference.h"

using namespace dbss;

namespace {

std::vector<uint64_t> hashes(const std::vector<uint8_t>& file) {
  ProgressiveDecoder d;
  REQUIRE(d.feed(file).ok());
  REQUIRE(d.finish().ok());
  std::vector<uint64_t> out;
  for (int l = 0; l <= d.ready_level(); ++l) {
    auto v = d.decode(static_cast<uint32_t>(l));
    REQUIRE(v.ok());
    out.push_back(test::hash_floats(v.value().positions.data(), v.value().positions.size()));
  }
  return out;
}

}  // namespace

TEST_CASE("a level in context coding decodes to the same bits as in the zstd codings") {
  struct Case {
    TriangleMesh mesh;
    uint8_t levels;
    int32_t amplitude;
    double crease_degrees;
  };
  const Case cases[] = {{test::jitter(test::torus(10, 5), 0.05f), 4, 40, 0},
                        {test::jitter(test::icosahedron(), 0.1f), 4, 3, 0},
                        {test::jitter(test::planar_grid(5, 4), 0.2f), 3, 100000, 0},  // boundary, EG tail
                        {test::cube(), 3, 20, 30}};                                   // creases: 1.2 with CREA
  for (const Case& c : cases) {
    const auto zstd = test::build_file(c.mesh, c.levels, c.amplitude, 0.01f, 3, c.crease_degrees, false);
    const auto context = test::build_file(c.mesh, c.levels, c.amplitude, 0.01f, 3, c.crease_degrees, true);
    REQUIRE(zstd != context);
    const format::Reader r = format::read_all(context);
    REQUIRE(r.complete());
    CHECK(r.header().version_minor == 2);
    CHECK(r.level(1).coding == format::DisplacementCoding::context);
    const auto expect = hashes(zstd);
    CHECK(expect.size() == c.levels + 1u);
    CHECK(hashes(context) == expect);

    // Fed in pieces of 7 bytes: each level as soon as its chunk is in.
    ProgressiveDecoder d;
    for (size_t at = 0; at < context.size(); at += 7)
      REQUIRE(d.feed({context.data() + at, std::min<size_t>(7, context.size() - at)}).ok());
    REQUIRE(d.finish().ok());
    REQUIRE(d.ready_level() == c.levels);
    auto finest = d.decode(c.levels);
    REQUIRE(finest.ok());
    CHECK(test::hash_floats(finest.value().positions.data(), finest.value().positions.size()) == expect.back());

    // The reference decoder, written from the spec's section 9b alone.
    const dbss_ref::Decoded ref = dbss_ref::decode(context);
    CHECK(ref.error.empty());
    REQUIRE(ref.levels.size() == expect.size());
    for (size_t l = 0; l < expect.size(); ++l) CHECK(dbss_ref::fnv1a64(ref.levels[l]) == expect[l]);
  }
}

TEST_CASE("the reference decoder reads the spec's example streams") {
  // dbss-format.md section 9b, "Examples", from the spec's text alone.
  const std::vector<uint8_t> first = {0x4f, 0x13, 0xbd, 0xa6, 0xd9, 0xa8, 0x05, 0xff,
                                      0xff, 0xdf, 0xff, 0xfc, 0x80, 0x00, 0x00, 0x00};
  std::vector<int32_t> q;
  CHECK(std::string(dbss_ref::detail::decode_context_stream(first, 8, q)).empty());
  CHECK(q == std::vector<int32_t>{0, 1, -1, 20, 0, 0, -3, 1 << 24});
  CHECK(std::string(dbss_ref::detail::decode_context_stream(std::vector<uint8_t>(7, 0), 1000, q)).empty());
  CHECK(q == std::vector<int32_t>(1000, 0));
  // Read for 20 values it runs out (compression); for 7, bytes are left
  // over (compression too).  (For 9 it is valid: the flush's last bytes
  // hold a few more zeros, which is why odd_count, not the stream, says n.)
  CHECK(std::string(dbss_ref::detail::decode_context_stream(first, 20, q)) == "compression");
  CHECK(std::string(dbss_ref::detail::decode_context_stream(first, 7, q)) == "compression");
}
