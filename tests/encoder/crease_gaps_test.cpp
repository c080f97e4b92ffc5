// Eleventh session's crease fixes (issue 16): a vertex in a gap of a line's
// chain retried with a lower quality floor (CreaseOptions::gap_snaps,
// crease_align.cpp 2a); the flat-fan corner tags judged flat against the
// fan's own plane (flat_fan_fit) and checked in their final configuration
// (flat_fan_check, creases.cpp tag_flat_fans).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../crease_shapes.h"
#include "../sampled_shapes.h"
#include "../test_data.h"
#include "dbss/decoder/level_refiner.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/encode.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"

using namespace dbss;

namespace {

// Length of the tagged control edges whose both ends lie within `tol` of
// the line x = 1, y = -1 (the roof block's vertical edge).
double tagged_on_vertical_edge(const Encoding& enc, double tol) {
  const format::Creases& c = enc.contents.creases;
  if (c.empty()) return 0;
  auto t = build_topology(static_cast<uint32_t>(enc.control.vertex_count()), enc.control.triangles).value();
  const auto p = [&](uint32_t v, int k) { return double(enc.control.positions[3 * size_t{v} + k]); };
  const auto on = [&](uint32_t v) { return std::abs(p(v, 0) - 1) < tol && std::abs(p(v, 1) + 1) < tol; };
  double sum = 0;
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t h = t.edge_half[e], u = t.triangles[h], w = t.triangles[next_half(h)];
    if (c.edge[e] && on(u) && on(w)) sum += std::abs(p(u, 2) - p(w, 2));
  }
  return sum;
}

// Each edge's level-1 stencil point's distance from its midpoint over its
// length, by the decoder's rules with the tags `tags`.
std::vector<double> stencil_offsets(const TriangleMesh& mesh, const format::Creases& tags) {
  std::vector<double> off;
  auto refiner = LevelRefiner::create(mesh, tags);
  REQUIRE(refiner.ok());
  off.assign(refiner.value().next_odd_count(), 0);
  std::vector<int32_t> q;
  refiner.value().refine(
      [&](uint32_t e, const double s[3], const double*, const float* u, const float* w) {
        double d2 = 0, l2 = 0;
        for (int k = 0; k < 3; ++k) {
          const double m = 0.5 * (double{u[k]} + double{w[k]});
          d2 += (s[k] - m) * (s[k] - m), l2 += (double{w[k]} - u[k]) * (double{w[k]} - u[k]);
        }
        off[e] = l2 > 0 ? std::sqrt(d2 / l2) : 0;
        return 0;
      },
      1.0f, q, 1);
  return off;
}

}  // namespace

TEST_CASE("a sampled roof block (seed 3): the vertical edge's chain has no gap, and level 1 stays near the roof") {
  const TriangleMesh truth = test::roof_block(8);
  const PointCloud pc = test::sampled(truth, 40000, 3);
  const double diagonal = 2 * std::sqrt(3.0);
  double covered[2] = {}, worst[2] = {}, mean[2] = {};
  for (int now = 0; now < 2; ++now) {
    EncodeOptions o = test::crease_options(30, 1);
    o.creases.gap_snaps = now == 1;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    covered[now] = tagged_on_vertical_edge(e.value(), 1e-3);
    const TriangleMesh level{e.value().levels.positions[1], e.value().levels.triangles[1]};
    const MeshDistance d = mesh_distance(level, truth, {100000, 1, 2});
    mean[now] = d.mean() / diagonal, worst[now] = d.max() / diagonal;
  }
  CAPTURE(covered[0], covered[1], mean[0], mean[1], worst[0], worst[1]);
  // The edge runs from z = -1 to z = 0.5.  When written: without the retry
  // a stretch of 0.17 had no vertex on the line (three moves refused at
  // quality 0.119-0.147); tagged along it 0.91 -> 1.30 (the rest of the
  // line's chain is not straight on it within 1e-3); level 1 2.04e-5 /
  // 2.28% -> 1.57e-5 / 0.63% (the other defaults on).
  CHECK(covered[1] > covered[0] + 0.25);
  CHECK(worst[1] < 0.5 * worst[0]);
  CHECK(worst[1] < 0.01);
  CHECK(mean[1] < 0.9 * mean[0]);
}

TEST_CASE("flat-fan corner tags: every chosen tag halves its worst stencil offset with the tags as they end up") {
  // The property the check pass (flat_fan_check) ensures; without it each
  // candidate was judged with every candidate tagged, and some tags were not
  // (when written: 17 of 24 on the cube at seed 1).
  size_t not_halved_unchecked = 0;
  for (const char* name : {"cube", "roof"}) {
    const TriangleMesh truth = std::string(name) == "cube" ? test::cube() : test::roof_block(8);
    for (uint32_t seed : {1u, 2u})
    for (bool check : {false, true}) {
      const PointCloud pc = test::sampled(truth, 40000, seed);
      EncodeOptions o = test::crease_options(30, 0);
      o.creases.flat_fan_check = check;
      auto e = encode_points(pc, o);
      REQUIRE(e.ok());
      const Encoding& enc = e.value();
      const format::Creases& tags = enc.contents.creases;
      REQUIRE(!tags.empty());
      auto t = build_topology(static_cast<uint32_t>(enc.control.vertex_count()), enc.control.triangles).value();
      std::vector<uint32_t> count(t.vertex_count, 0);
      for (uint32_t i = 0; i < t.edge_count(); ++i)
        if (tags.edge[i]) ++count[t.triangles[t.edge_half[i]]], ++count[t.triangles[next_half(t.edge_half[i])]];
      // The flat-fan tags: corners with no crease edge.
      format::Creases without = tags;
      size_t flat = 0;
      for (uint32_t v = 0; v < t.vertex_count; ++v)
        if (tags.corner[v] && count[v] == 0) without.corner[v] = 0, ++flat;
      CHECK(flat == enc.creases.flat_corners);
      const std::vector<double> before = stencil_offsets(enc.control, without), after = stencil_offsets(enc.control, tags);
      std::vector<double> worst_before(t.vertex_count, 0), worst_after(t.vertex_count, 0);
      for (uint32_t i = 0; i < t.edge_count(); ++i)
        for (uint32_t v : {t.triangles[t.edge_half[i]], t.triangles[next_half(t.edge_half[i])]})
          worst_before[v] = std::max(worst_before[v], before[i]), worst_after[v] = std::max(worst_after[v], after[i]);
      size_t not_halved = 0;
      for (uint32_t v = 0; v < t.vertex_count; ++v)
        if (tags.corner[v] && count[v] == 0) not_halved += !(worst_after[v] < 0.5 * worst_before[v]);
      CAPTURE(name, seed, flat, enc.creases.flat_corners_dropped);
      if (check) CHECK(not_halved == 0);
      else not_halved_unchecked += not_halved;
    }
  }
  CHECK(not_halved_unchecked > 0);
}

TEST_CASE("the libcgal-demo fandisk (seed 1): a fan tilted by a neighbour snapped just off its plane still counts as flat") {
  const auto path = test::scan_data("data/meshes/fandisk.off");
  if (!path) return;
  auto read = read_mesh(*path);
  REQUIRE(read.ok());
  const TriangleMesh truth = std::move(read).value();
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < truth.positions.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], double{truth.positions[i]}), hi[i % 3] = std::max(hi[i % 3], double{truth.positions[i]});
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const PointCloud pc = test::sampled(truth, 40000, 1);
  double worst[2] = {}, mean[2] = {};
  size_t flat[2] = {};
  for (int now = 0; now < 2; ++now) {
    EncodeOptions o = test::crease_options(30, 1);
    o.creases.flat_fan_fit = now == 1;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    flat[now] = e.value().creases.flat_corners;
    const TriangleMesh level{e.value().levels.positions[1], e.value().levels.triangles[1]};
    const MeshDistance d = mesh_distance(level, truth, {100000, 1, 2});
    mean[now] = d.mean() / diagonal, worst[now] = d.max() / diagonal;
  }
  CAPTURE(flat[0], flat[1], mean[0], mean[1], worst[0], worst[1]);
  CHECK(flat[1] > flat[0]);
  CHECK(worst[1] < 0.8 * worst[0]);
  CHECK(mean[1] < 1.02 * mean[0]);
}
