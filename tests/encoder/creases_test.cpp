// Crease detection from points (dbss/encoder/creases.h) and its path through
// the encoder: none on smooth shapes (files byte-identical with it off),
// tags on machined ones, and the decoder reproducing the encoder's levels
// from a 1.1 file bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../crease_shapes.h"
#include "../sampled_shapes.h"
#include "../shapes.h"
#include "dbss/decoder/progressive.h"
#include "dbss/encoder/creases.h"
#include "dbss/encoder/encode.h"
#include "dbss/format/reader.h"
#include "dbss/format/writer.h"

using namespace dbss;

TEST_CASE("no crease on smooth shapes: the file is byte-identical with --crease-angle off") {
  for (const TriangleMesh& m : {test::uv_sphere(24, 32), test::torus(48, 24)}) {
    const PointCloud pc = test::sampled(m, 12000, 3);
    auto on = encode_points(pc, test::crease_options(30, 2));
    auto off = encode_points(pc, test::crease_options(0, 2));
    REQUIRE(on.ok());
    REQUIRE(off.ok());
    CHECK(on.value().creases.creases == 0);
    CHECK(on.value().contents.creases.empty());
    // 0, or 2 if a level took the context coder (no CREA needs 1).
    CHECK(on.value().contents.header.version_minor == format::minimum_version_minor(on.value().contents));
    CHECK(on.value().contents.header.version_minor != format::kCreaseVersionMinor);
    CHECK(on.value().bytes == off.value().bytes);
  }
}

TEST_CASE("a sampled cube gets crease tags, a 1.1 file the decoder reproduces bit for bit") {
  const PointCloud pc = test::sampled(test::cube(), 20000, 3);
  auto e = encode_points(pc, test::crease_options(30, 2));
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  CHECK(enc.creases.creases > 12);  // the control mesh's edges along the cube's 12 edges
  REQUIRE(!enc.contents.creases.empty());
  auto r = format::read_all(enc.bytes);
  REQUIRE(r.status().ok());
  CHECK(r.header().version_minor >= 1);  // 1, or 2 if a level took the context coder
  CHECK(r.header().version_minor == format::minimum_version_minor(enc.contents));
  CHECK(r.creases() == enc.contents.creases);
  // Tagged edges lie on the cube's edges: both ends near two faces.
  auto t = build_topology(static_cast<uint32_t>(enc.control.vertex_count()), enc.control.triangles).value();
  size_t on_edge = 0, tagged = 0;
  for (uint32_t i = 0; i < t.edge_count(); ++i) {
    if (!enc.contents.creases.edge[i]) continue;
    ++tagged;
    bool both = true;
    for (uint32_t v : {t.triangles[t.edge_half[i]], t.triangles[next_half(t.edge_half[i])]}) {
      int near_faces = 0;
      for (int k = 0; k < 3; ++k) near_faces += std::abs(std::abs(enc.control.positions[3 * v + k]) - 1.0) < 0.05;
      both = both && near_faces >= 2;
    }
    on_edge += both;
  }
  // Most, not all: today's control mesh has few edges along the features,
  // and the test tags some that start on an edge and end beside it (61 of
  // 89 here when written; the reason the option is off by default).
  CHECK(on_edge * 2 >= tagged);
  // The decoder, from the file alone, gives the encoder's levels.
  ProgressiveDecoder d;
  REQUIRE(d.feed(enc.bytes).ok());
  REQUIRE(d.finish().ok());
  for (uint32_t l = 0; l <= enc.level_count; ++l) {
    auto v = d.decode(l);
    REQUIRE(v.ok());
    CHECK(std::equal(v.value().positions.begin(), v.value().positions.end(), enc.levels.positions[l].begin(),
                     enc.levels.positions[l].end()));
  }
}

TEST_CASE("transfer_creases follows a renumbering of vertices and triangles") {
  const TriangleMesh m = test::roof_block(4);
  const format::Creases c = test::creases_from_dihedral(m, 30);
  // Reverse the vertex order and rotate every triangle's corners.
  TriangleMesh r;
  const uint32_t n = static_cast<uint32_t>(m.vertex_count());
  r.positions.resize(m.positions.size());
  for (uint32_t v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) r.positions[3 * size_t{n - 1 - v} + k] = m.positions[3 * size_t{v} + k];
  for (size_t f = m.triangle_count(); f-- > 0;)
    r.triangles.insert(r.triangles.end(), {n - 1 - m.triangles[3 * f + 1], n - 1 - m.triangles[3 * f + 2], n - 1 - m.triangles[3 * f]});
  const format::Creases moved = transfer_creases(m, c, r);
  CHECK(moved == test::creases_from_dihedral(r, 30));
  CHECK(std::count(moved.edge.begin(), moved.edge.end(), 1) == std::count(c.edge.begin(), c.edge.end(), 1));
}
