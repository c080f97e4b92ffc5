#include <catch2/catch.hpp>

#include <algorithm>

#include "../shapes.h"
#include "dbss/decoder/progressive.h"
#include "dbss/format/reader.h"
#include "file_builder.h"
#include "kernel_choice.h"
#include "reference.h"

using namespace dbss;

TEST_CASE("progressive decoding: levels become ready as bytes arrive and equal whole-file decoding") {
  const auto file = test::build_file(test::jitter(test::torus(10, 5), 0.05f), 4, 40, 0.01f);
  std::vector<uint64_t> whole;
  for (int l = 0; l <= 4; ++l) {
    auto m = decode_bytes(file, l);
    REQUIRE(m.ok());
    whole.push_back(test::hash_floats(m.value().positions.data(), m.value().positions.size()));
  }
  ProgressiveDecoder d;
  int last_ready = -1;
  for (size_t at = 0; at < file.size(); at += 37) {
    REQUIRE(d.feed({file.data() + at, std::min<size_t>(37, file.size() - at)}).ok());
    const int ready = d.ready_level();
    REQUIRE(ready >= last_ready);
    if (ready > last_ready) {
      auto v = d.decode_finest();
      REQUIRE(v.ok());
      CHECK(v.value().level == static_cast<uint32_t>(ready));
      CHECK(test::hash_floats(v.value().positions.data(), v.value().positions.size()) == whole[ready]);
      last_ready = ready;
    }
  }
  REQUIRE(d.finish().ok());
  CHECK(last_ready == 4);
  // Any order of levels gives the same bits.
  for (uint32_t l : {2u, 0u, 3u, 1u, 4u, 4u, 0u}) {
    auto v = d.decode(l);
    REQUIRE(v.ok());
    CHECK(test::hash_floats(v.value().positions.data(), v.value().positions.size()) == whole[l]);
  }
  CHECK(d.decode(5).status().code() == ErrorCode::bad_state);
}

TEST_CASE("keep_levels returns the same meshes") {
  const auto file = test::build_file(test::icosahedron(), 3, 20, 0.02f);
  DecoderOptions keep;
  keep.keep_levels = true;
  ProgressiveDecoder a(keep), b;
  REQUIRE(a.feed(file).ok());
  REQUIRE(b.feed(file).ok());
  for (uint32_t l : {3u, 1u, 2u, 0u, 3u}) {
    auto x = a.decode(l);
    auto y = b.decode(l);
    REQUIRE(x.ok());
    REQUIRE(y.ok());
    CHECK(x.value().copy() == y.value().copy());
  }
}

TEST_CASE("a truncated file decodes its complete levels: counts must match the header") {
  const auto file = test::build_file(test::torus(10, 5), 3, 10, 0.01f);
  ProgressiveDecoder d;
  d.feed({file.data(), file.size() - 5});
  CHECK(d.finish().code() == ErrorCode::truncated);
  CHECK(d.ready_level() == 2);
  auto m = d.decode(2);
  REQUIRE(m.ok());
  CHECK(m.value().vertex_count() == 800);
  CHECK(m.value().triangle_count() == 1600);

  // A header whose edge count disagrees with the control mesh: bad_mesh.
  auto bytes = file;
  auto reader = format::read_all(bytes);
  format::FileContents c;
  c.header = reader.header();
  c.header.control_edge_count += 1;  // still a plausible triangle mesh count
  c.control_mesh.assign(reader.control_payload().begin(), reader.control_payload().end());
  c.header.level_count = 0;
  auto bad = format::serialize(c);
  REQUIRE(bad.ok());
  auto r = decode_bytes(bad.value(), 0);
  CHECK(r.status().code() == ErrorCode::bad_mesh);
}

// The progressive decoder evaluates stencils and normals straight from the
// half-edge tables over face ranges on several threads; the reference
// decoder of spec/reference (written from the spec alone, one thread) is its
// independent reference.  Levels large enough for the decoder to split work
// over threads (> 65,536 faces), closed and bordered, with and without
// displacements.
TEST_CASE("progressive decoder equals the reference decoder bit for bit on 1 to 3 threads") {
  struct Case {
    TriangleMesh mesh;
    int32_t amplitude;
  };
  const Case cases[] = {{test::jitter(test::torus(40, 20), 0.05f), 40},
                        {test::jitter(test::planar_grid(30, 26), 0.2f), 50},
                        {test::jitter(test::bipyramid(9), 0.1f, 9), 0}};
  for (const Case& c : cases) {
    const uint8_t levels = c.mesh.triangle_count() > 1000 ? 4 : 6;
    const auto file = test::build_file(c.mesh, levels, c.amplitude, 0.01f);
    // Every level by the reference decoder.
    const dbss_ref::Decoded ref = dbss_ref::decode(file);
    REQUIRE(ref.error.empty());
    REQUIRE(ref.levels.size() == levels + 1u);
    std::vector<std::vector<float>> positions;
    std::vector<std::vector<uint32_t>> triangles;
    for (const dbss_ref::Mesh& m : ref.levels) positions.push_back(m.positions), triangles.push_back(m.triangles);
    for (unsigned threads : {1u, 2u, 3u}) {
      DecoderOptions o;
      o.threads = threads;
      o.kernels = test::kernels_under_test();
      ProgressiveDecoder d(o);
      REQUIRE(d.feed(file).ok());
      for (uint32_t l : {static_cast<uint32_t>(levels), 1u, 2u, 3u, static_cast<uint32_t>(levels)}) {
        auto v = d.decode(l);
        REQUIRE(v.ok());
        INFO("threads " << threads << ", level " << l);
        CHECK(test::hash_floats(v.value().positions.data(), v.value().positions.size()) ==
              test::hash_floats(positions[l].data(), positions[l].size()));
        CHECK(std::equal(v.value().triangles.begin(), v.value().triangles.end(), triangles[l].begin(),
                         triangles[l].end()));
      }
    }
  }
}

TEST_CASE("reset: one decoder over several streams equals a fresh decoder for each") {
  const auto big = test::build_file(test::jitter(test::torus(16, 9), 0.05f), 4, 40, 0.01f);
  const auto small = test::build_file(test::jitter(test::bipyramid(7), 0.1f, 3), 5, 30, 0.02f);
  const auto bordered = test::build_file(test::jitter(test::planar_grid(12, 9), 0.2f), 3, 50, 0.01f);
  const auto fresh = [](const std::vector<uint8_t>& file, uint32_t level) {
    auto m = decode_bytes(file, static_cast<int>(level));
    REQUIRE(m.ok());
    return m.value();
  };
  for (unsigned threads : {1u, 2u}) {
    DecoderOptions o;
    o.threads = threads;
    ProgressiveDecoder d(o);
    // Shapes that grow, shrink and grow again, so the kept storage is both
    // too large and too small for the next stream.
    for (const auto* file : {&big, &small, &bordered, &big, &big, &small}) {
      const uint32_t finest = static_cast<uint32_t>(format::read_all(*file).levels_ready());
      REQUIRE(d.feed(*file).ok());
      REQUIRE(d.finish().ok());
      for (uint32_t l : {finest, 1u, finest}) {
        auto v = d.decode(l);
        REQUIRE(v.ok());
        INFO("threads " << threads << ", level " << l << " of " << finest);
        CHECK(v.value().copy() == fresh(*file, l));
      }
      d.reset();
      CHECK(d.ready_level() == -1);
    }
    // A stream that failed leaves nothing behind after reset.
    auto broken = big;
    broken[broken.size() / 2] ^= 0x40;
    CHECK_FALSE(d.feed(broken).ok());
    CHECK_FALSE(d.status().ok());
    d.reset();
    CHECK(d.status().ok());
    REQUIRE(d.feed(small).ok());
    auto v = d.decode(3);
    REQUIRE(v.ok());
    CHECK(v.value().copy() == fresh(small, 3));
  }
}
