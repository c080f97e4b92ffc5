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

TEST_CASE("a sampled roof block: corner tags on flat lopsided fans keep level 1 inside the roof") {
  const TriangleMesh truth = test::roof_block(8);
  const PointCloud pc = test::sampled(truth, 40000, 1);
  const double diagonal = 2 * std::sqrt(3.0);
  double mean[2] = {}, worst[2] = {};
  size_t flat[2] = {};
  std::vector<float> control[2];
  for (int now = 0; now < 2; ++now) {
    EncodeOptions o = test::crease_options(30, 1);
    o.creases.flat_corners = now == 1;
    // The tagged mesh's second shaping pass (crease_shape.h) mends part of
    // the same lopsided fans: with it, level 1's worst is 0.83% without the
    // tags and 0.63% with them (x0.76).  Off here, to measure the tags
    // against the fans as they were written against.
    o.creases.shape_after_tags = false;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    flat[now] = enc.creases.flat_corners;
    control[now] = enc.control.positions;
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
      CHECK(lone >= flat[1]);
    }
    const TriangleMesh level{enc.levels.positions[1], enc.levels.triangles[1]};
    const MeshDistance d = mesh_distance(level, truth, {100000, 1, 2});
    mean[now] = d.mean() / diagonal, worst[now] = d.max() / diagonal;
  }
  CAPTURE(mean[0], mean[1], worst[0], worst[1], flat[1]);
  CHECK(flat[0] == 0);
  CHECK(flat[1] > 5);
  // The tags move no vertex: the same control mesh.
  CHECK(control[0] == control[1]);
  // When written (seed 1): level 1 2.91e-5 / 1.34% -> 2.67e-5 / 0.68%.
  CHECK(worst[1] < 0.01);
  CHECK(worst[1] < 0.7 * worst[0]);
  CHECK(mean[1] < mean[0]);
}
