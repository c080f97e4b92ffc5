#include <catch2/catch.hpp>

#include "../shapes.h"
#include "dbss/decoder/progressive.h"
#include "file_builder.h"

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

TEST_CASE("a truncated file decodes its complete levels; counts must match the header") {
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
