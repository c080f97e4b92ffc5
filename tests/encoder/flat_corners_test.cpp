// Corner tags on smooth control vertices of flat, lopsided fans
// (CreaseOptions::flat_corners, creases.cpp): the edges at such a vertex
// take the butterfly's eight-point rule instead of the extraordinary rule,
// whose whole-ring stencil put the roof's level-1 odd vertices past the
// eaves in the face's plane, beyond any displacement's reach.
#include <catch2/catch.hpp>

#include <cmath>

#include "../crease_shapes.h"
#include "../sampled_shapes.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/encode.h"
#include "dbss/measure/mesh_distance.h"

using namespace dbss;

namespace {

// Level 1 of the sampled roof block with the flat-fan corner tags off
// ([0]) and on ([1]): its mean and worst distance to the truth over the
// diagonal, the tags made, and the control mesh.
struct RoofRun {
  double mean[2] = {}, worst[2] = {};
  size_t flat[2] = {};
  std::vector<float> control[2];
};

RoofRun roof_with_and_without_tags(bool shape_after_tags) {
  const TriangleMesh truth = test::roof_block(8);
  const PointCloud pc = test::sampled(truth, 40000, 1);
  const double diagonal = 2 * std::sqrt(3.0);
  RoofRun r;
  for (int now = 0; now < 2; ++now) {
    EncodeOptions o = test::crease_options(30, 1);
    o.creases.flat_corners = now == 1;
    o.creases.shape_after_tags = shape_after_tags;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    r.flat[now] = enc.creases.flat_corners;
    r.control[now] = enc.control.positions;
    // Every vertex tagged for its fan has no crease edge: the tags add
    // corners, never change a crease.
    if (now == 1) {
      const format::Creases& c = enc.contents.creases;
      REQUIRE(!c.empty());
      auto t = build_topology(static_cast<uint32_t>(enc.control.vertex_count()), enc.control.triangles).value();
      std::vector<uint32_t> count(t.vertex_count, 0);
      for (uint32_t i = 0; i < t.edge_count(); ++i)
        if (c.edge[i]) ++count[t.triangles[t.edge_half[i]]], ++count[t.triangles[next_half(t.edge_half[i])]];
      size_t lone = 0;
      for (uint32_t v = 0; v < t.vertex_count; ++v) lone += c.corner[v] && count[v] == 0;
      CHECK(lone >= r.flat[1]);
    }
    const TriangleMesh level{enc.levels.positions[1], enc.levels.triangles[1]};
    const MeshDistance d = mesh_distance(level, truth, {100000, 1, 2});
    r.mean[now] = d.mean() / diagonal, r.worst[now] = d.max() / diagonal;
  }
  return r;
}

}  // namespace

TEST_CASE("a sampled roof block: corner tags on flat lopsided fans keep level 1 inside the roof") {
  // The tagged mesh's second shaping pass (crease_shape.h) mends part of
  // the same lopsided fans; off here, to measure the tags against the fans
  // as they were written against (the defaults: the next case).
  const RoofRun r = roof_with_and_without_tags(false);
  CAPTURE(r.mean[0], r.mean[1], r.worst[0], r.worst[1], r.flat[1]);
  CHECK(r.flat[0] == 0);
  CHECK(r.flat[1] > 5);
  // The tags move no vertex: the same control mesh.
  CHECK(r.control[0] == r.control[1]);
  // When written (seed 1): level 1 2.91e-5 / 1.34% -> 2.67e-5 / 0.68%.
  CHECK(r.worst[1] < 0.01);
  CHECK(r.worst[1] < 0.7 * r.worst[0]);
  CHECK(r.mean[1] < r.mean[0]);
}

TEST_CASE("a sampled roof block under the defaults: the flat-fan corner tags still lower level 1's worst") {
  // With the shaping pass (and the off-point settle) on, the fans are
  // less lopsided before the tags are chosen; the tags must still pay.
  // Measured (seed 1): level 1 1.64e-5 / 0.92% -> 1.50e-5 / 0.84% (x0.905);
  // with the shaping pass off (the case above) 0.83% -> 0.44%.
  const RoofRun r = roof_with_and_without_tags(true);
  CAPTURE(r.mean[0], r.mean[1], r.worst[0], r.worst[1], r.flat[1]);
  CHECK(r.flat[0] == 0);
  CHECK(r.flat[1] > 0);
  CHECK(r.control[0] == r.control[1]);
  CHECK(r.worst[1] < 0.01);
  CHECK(r.worst[1] < 0.95 * r.worst[0]);
  CHECK(r.mean[1] < r.mean[0]);
}
