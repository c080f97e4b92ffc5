// CreaseOptions::clamp_to_points (issue 16): a tagged control mesh's
// vertices clamped onto the points' axis-plane box faces before Draco.
// Draco's grid starts at the control vertices' minimum and spans their
// largest extent; a crease vertex snapped a little past a face of a cube
// shifts the grid, and every vertex of the cube's faces then rounds onto a
// grid line 1e-5-2e-5 off its face, an offset no level can store (0.02 of
// the displacement step).  With the clamp, the faces' vertices land on
// their faces exactly.  Sampled as crease_bench samples (seed 2, where the
// offset was measured: bench/crease_bench.md, thirteenth session).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../crease_shapes.h"
#include "../sampled_shapes.h"
#include "../shapes.h"
#include "dbss/encoder/encode.h"

using namespace dbss;

namespace {

// The largest distance of a control vertex lying on a face of the cube
// [-1, 1]^3 (within 1e-4 of it: a fifth of the grid step, so no vertex
// beside an edge, a grid line or two inside, counts) from that face's plane.
double face_offset(const TriangleMesh& control) {
  double worst = 0;
  for (size_t v = 0; v < control.vertex_count(); ++v)
    for (int a = 0; a < 3; ++a) {
      const double off = 1.0 - std::abs(double{control.positions[3 * v + a]});
      if (std::abs(off) < 1e-4) worst = std::max(worst, std::abs(off));
    }
  return worst;
}

}  // namespace

TEST_CASE("a sampled cube's tagged control mesh clamped onto the points' box faces lands on its faces exactly") {
  const PointCloud pc = test::sampled(test::cube(), 40000, 2);
  EncodeOptions o = test::crease_options(30, 1);
  auto off = encode_points(pc, o);
  REQUIRE(off.ok());
  REQUIRE(off.value().creases.creases > 0);
  // Without the clamp: the grid is shifted off the faces.
  CHECK(face_offset(off.value().control) > 5e-6);
  CHECK(off.value().creases.clamped_to_points == 0);

  o.creases.clamp_to_points = true;
  auto on = encode_points(pc, o);
  REQUIRE(on.ok());
  REQUIRE(on.value().creases.creases > 0);
  CHECK(on.value().creases.clamped_to_points > 0);
  CHECK(face_offset(on.value().control) < 1e-7);
}

TEST_CASE("a smooth shape is not clamped: a sampled sphere's file is the same with clamp_to_points on") {
  // No tag, so the untagged path (rounding along the surface) runs either way.
  const PointCloud pc = test::sampled(test::uv_sphere(48, 64), 8000, 1);
  EncodeOptions o = test::crease_options(30, 1);
  auto a = encode_points(pc, o);
  o.creases.clamp_to_points = true;
  auto b = encode_points(pc, o);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(a.value().creases.creases == 0);
  CHECK(b.value().creases.clamped_to_points == 0);
  CHECK(a.value().bytes == b.value().bytes);
}
