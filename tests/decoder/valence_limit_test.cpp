// The valence limit of spec/decoding.md section 2 (at most 64), at the
// edge: a bipyramid's apexes have the valence of its equator.
#include <catch2/catch.hpp>

#include "../shapes.h"
#include "dbss/decoder/topology.h"

using namespace dbss;

TEST_CASE("valence 64 is accepted, valence 65 is bad_mesh naming the vertex") {
  const TriangleMesh ok = test::bipyramid(kMaxValence);
  auto t = build_topology(static_cast<uint32_t>(ok.vertex_count()), ok.triangles);
  REQUIRE(t.ok());
  CHECK(t.value().vertex_valence[kMaxValence] == kMaxValence);
  const TriangleMesh over = test::bipyramid(kMaxValence + 1);
  auto r = build_topology(static_cast<uint32_t>(over.vertex_count()), over.triangles);
  CHECK(r.status().code() == ErrorCode::bad_mesh);
  CHECK_THAT(r.status().message(), Catch::Contains("vertex 65") && Catch::Contains("over 64"));
}
