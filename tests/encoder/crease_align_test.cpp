// The control mesh aligned to the feature lines (dbss/encoder/crease_align.h)
// before the crease tags are found: on a sampled cube the tagged edges lie on
// the cube's edges and form long chains (few darts), and nothing moves on a
// smooth shape.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "../crease_shapes.h"
#include "../sampled_shapes.h"
#include "../shapes.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/crease_align.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/sampling.h"
#include "dbss/measure/mesh_distance.h"

using namespace dbss;

namespace {

// Which of the cube's 12 edges (|x| = |y| = 1 and so on, within tol) holds
// the point: a bit per face pair it is on, 0 when on none.
int cube_faces(const float* p, double tol) {
  int faces = 0;
  for (int k = 0; k < 3; ++k)
    if (std::abs(std::abs(p[k]) - 1.0) < tol) faces |= (p[k] > 0 ? 1 : 2) << (2 * k);
  return faces;
}

int bits(int x) {
  int n = 0;
  for (; x; x &= x - 1) ++n;
  return n;
}

}  // namespace

TEST_CASE("a sampled cube: tagged control edges run along the cube's edges in chains") {
  const PointCloud pc = test::sampled(test::cube(), 40000, 5);
  EncodeOptions o = test::crease_options(30, 1);
  auto e = encode_points(pc, o);
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  CHECK(enc.creases.aligned > 100);
  CHECK(enc.creases.chain_edges > 100);
  REQUIRE(!enc.contents.creases.empty());
  auto t = build_topology(static_cast<uint32_t>(enc.control.vertex_count()), enc.control.triangles).value();
  // Tolerance: Draco's rounding of the control positions.
  const double tol = 4.0 / (1 << enc.control_bits) + 1e-4;
  double along = 0;
  size_t tagged = 0, on_edge = 0;
  for (uint32_t i = 0; i < t.edge_count(); ++i) {
    if (!enc.contents.creases.edge[i]) continue;
    ++tagged;
    const uint32_t u = t.triangles[t.edge_half[i]], w = t.triangles[next_half(t.edge_half[i])];
    const float* pu = &enc.control.positions[3 * size_t{u}];
    const float* pw = &enc.control.positions[3 * size_t{w}];
    // Both ends on one of the cube's edges (two faces in common).
    if (bits(cube_faces(pu, tol) & cube_faces(pw, tol)) >= 2) {
      ++on_edge;
      along += std::sqrt(std::pow(pu[0] - pw[0], 2.0) + std::pow(pu[1] - pw[1], 2.0) + std::pow(pu[2] - pw[2], 2.0));
    }
  }
  // Before alignment: 61 of 89 tagged edges on the cube's edges, 8 of the
  // 24 units of edge length covered, 106 darts.
  CHECK(on_edge >= tagged * 8 / 10);
  CHECK(along >= 0.8 * 24);
  CHECK(enc.creases.darts * 2 < enc.creases.creases);
  // Crease ends in line with another end (or with a corner) one or two
  // edges on are bridged: with only the one-edge rule between two ends the
  // bench's cube closed 1 gap and kept 94 darts (bench/crease_bench.md);
  // this sample: 14 closed, 84 darts of 406 tags.
  CAPTURE(enc.creases.gaps_closed, enc.creases.darts, enc.creases.creases);
  CHECK(enc.creases.gaps_closed >= 8);
  CHECK(enc.creases.darts * 4 < enc.creases.creases);
  CHECK(enc.creases.corners >= 4);  // of 8: the vertices QEM left within reach of a corner
}

TEST_CASE("alignment moves nothing on smooth shapes") {
  for (const TriangleMesh& m : {test::uv_sphere(24, 32), test::torus(48, 24)}) {
    const PointCloud pc = test::sampled(m, 12000, 5);
    const PointIndex index(pc);
    TriangleMesh control = m;  // the shape's own mesh as a control mesh: vertices on the points' surface
    CreaseOptions o;
    o.angle_degrees = 30;
    AlignStats st;
    std::vector<std::array<uint32_t, 2>> chains;
    align_to_features(control, index, o, &st, &chains);
    CHECK(st.line_vertices == 0);
    CHECK(st.corner_vertices == 0);
    CHECK(st.snapped == 0);
    CHECK(chains.empty());
    CHECK(control.positions == m.positions);
    CHECK(control.triangles == m.triangles);
  }
}

TEST_CASE("a sampled cube's refined levels: creases and one-sided sampling keep the edges sharp") {
  const TriangleMesh truth = test::cube();
  const PointCloud pc = test::sampled(truth, 40000, 5);
  const double diagonal = 2 * std::sqrt(3.0);
  double mean[2] = {}, worst[2] = {};  // level 2's, over the diagonal
  for (int on = 0; on < 2; ++on) {
    EncodeOptions o = test::crease_options(on ? 30 : 0, 2);
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    const TriangleMesh level{enc.levels.positions[2], enc.levels.triangles[2]};
    const MeshDistance d = mesh_distance(level, truth, {40000, 1, 2});
    mean[on] = d.mean() / diagonal, worst[on] = d.max() / diagonal;
  }
  INFO("level 2 off: " << mean[0] << " / " << worst[0] << ", on: " << mean[1] << " / " << worst[1]);
  // When written: mean 1.02e-4 off, 5.1e-5 on.  The Hausdorff distance is
  // not checked: a few odd vertices beside a chain's gap still overshoot
  // (3.5% off, 3.9% on here; under 1% with crease_bench's seed).
  CHECK(mean[1] < 0.7 * mean[0]);
}

TEST_CASE("point normals: the same floats on one thread and on two, and each side's own normal at a cube's edge") {
  const PointCloud pc = test::sampled(test::cube(), 24000, 5);  // three pieces of work allowed, two threads used
  const PointIndex index(pc);
  const std::vector<float> one = estimate_point_normals(index, 1), two = estimate_point_normals(index, 2);
  REQUIRE(one.size() == 3 * pc.size());
  CHECK(one == two);
  // Every point of a cube lies on a face: its normal is that face's axis
  // (the robust plane, not the blend of two faces next to an edge).  At
  // this density some 6% of the points lie within a spacing of an edge (12
  // edges, two sides, a spacing of 0.016 on 6 units of area), where a
  // least-squares normal tilts; the robust one missed on 1.2%.
  size_t off_axis = 0;
  for (size_t i = 0; i < pc.size(); ++i) {
    const float m = std::max({std::abs(one[3 * i]), std::abs(one[3 * i + 1]), std::abs(one[3 * i + 2])});
    off_axis += m < 0.99f;
  }
  INFO(off_axis << " of " << pc.size() << " normals off every axis");
  CHECK(off_axis < 3 * pc.size() / 100);
}

TEST_CASE("a sampled cube: vertices beside a line are merged into it, and the control mesh stays a closed sphere") {
  const PointCloud pc = test::sampled(test::cube(), 40000, 5);
  size_t darts[2] = {}, collapses[2] = {};
  for (int on = 0; on < 2; ++on) {
    EncodeOptions o = test::crease_options(30, 0);
    o.creases.collapse = on;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    darts[on] = enc.creases.darts, collapses[on] = enc.creases.align_collapses;
    auto t = build_topology(static_cast<uint32_t>(enc.control.vertex_count()), enc.control.triangles);
    REQUIRE(t.ok());
    // Closed (every edge has a twin) and genus 0: V - E + F = 2.
    for (uint32_t h = 0; h < t.value().twin.size(); ++h) CHECK(t.value().twin[h] != kNoHalfEdge);
    CHECK(int64_t(t.value().vertex_count) - int64_t(t.value().edge_count()) + int64_t(enc.control.triangle_count()) == 2);
  }
  // When written (seed 5): 171 merges on the bench's seed took its darts from 110 to 58.
  CAPTURE(darts[0], darts[1], collapses[1]);
  CHECK(collapses[0] == 0);
  CHECK(collapses[1] > 50);
  CHECK(darts[1] * 10 < darts[0] * 8);
}

TEST_CASE("sampling beside a cube's edge: the two sides' planes, not a fit that rounds the edge") {
  const PointCloud pc = test::sampled(test::cube(), 40000, 5);
  const PointIndex index(pc);
  const std::vector<float> normals = estimate_point_normals(index, 2);
  const double s = 1 / std::sqrt(2.0);
  struct Case {
    double p[3], n[3], want;
  };
  // On the bisector 0.01 inside the edge x = y = 1; on the face y = 1 a
  // point spacing (0.016) from that edge, 0.004 inside; the same 0.03 outside.
  const Case cases[] = {{{1 - 0.01 * s, 1 - 0.01 * s, 0.1}, {s, s, 0}, 0.01},
                        {{1 - 0.016, 1 - 0.004, 0.2}, {0, 1, 0}, 0.004},
                        {{1 - 0.016, 1 + 0.03, -0.3}, {0, 1, 0}, -0.03}};
  for (const Case& c : cases) {
    double got[2];
    for (int wedge = 0; wedge < 2; ++wedge) {
      PointSides sides{&normals, std::cos(30 * 3.14159265358979323846 / 180), wedge == 1};
      SampleScratch scratch;
      got[wedge] = sample_displacement(index, c.p, c.n, 0.05, 0.05, scratch, true, &sides).distance;
    }
    CAPTURE(c.want, got[0], got[1]);
    // When written: on the bisector 0.0085 with the wedge, 0.0043 without
    // (want 0.01); beside it within 1e-4 either way.
    CHECK(std::abs(got[1] - c.want) < 2.5e-3);
    CHECK(std::abs(got[1] - c.want) <= std::abs(got[0] - c.want) + 1e-4);
  }
}

TEST_CASE("a sampled cube: relaxing the flat vertices beside a line lowers level 1's error") {
  // QEM leaves vertices beside a cube's edge with a few short edges towards
  // it and a few long ones across the face; not moved onto the line, they
  // were not relaxed, and the butterfly's extraordinary rule at them put odd
  // vertices past the edge in the face's plane (crease_bench: 0.128 out).
  const TriangleMesh truth = test::cube();
  const PointCloud pc = test::sampled(truth, 40000, 5);
  const double diagonal = 2 * std::sqrt(3.0);
  double mean[2] = {}, worst[2] = {};  // level 1's, over the diagonal
  size_t relaxed[2] = {};
  for (int on = 0; on < 2; ++on) {
    EncodeOptions o = test::crease_options(30, 1);
    o.creases.relax_beside_lines = on;
    // Measured against the baseline it was written for: the corner tags on
    // flat fans (tenth session) fix part of the same overshoot on their
    // own (level 1 1.34e-5 without the relaxation, 1.26e-5 with it).
    o.creases.flat_corners = false;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    relaxed[on] = enc.creases.align_relaxed;
    const TriangleMesh level{enc.levels.positions[1], enc.levels.triangles[1]};
    const MeshDistance d = mesh_distance(level, truth, {40000, 1, 2});
    mean[on] = d.mean() / diagonal, worst[on] = d.max() / diagonal;
  }
  INFO("level 1 beside-line relaxation off: " << mean[0] << " / " << worst[0] << " (" << relaxed[0] << " moves), on: " << mean[1]
                                              << " / " << worst[1] << " (" << relaxed[1] << " moves)");
  // When written: mean 2.44e-5 -> 1.77e-5, 274 -> 2252 moves.  The
  // Hausdorff distance is not checked: with this seed it rose (2.52% ->
  // 2.99%, one worst odd vertex elsewhere); with crease_bench's it fell
  // 3.18% -> 1.12%.
  CHECK(relaxed[1] > 4 * relaxed[0]);
  CHECK(mean[1] < 0.85 * mean[0]);
}

TEST_CASE("a sampled cube: flips toward valence 6 beside the lines, and level 1 nearer the cube") {
  // Main's defaults until the ninth session (no valence flips, flat
  // vertices beside a line not relaxed) against today's.  QEM crowds the
  // cube's edges with vertices and leaves few inside its faces, whose
  // valences reach 8-10 with lopsided rings.  Then untag_flat: short flat
  // edges next to a line are tagged when their points see both faces, each
  // a spur ending in a dart.
  const TriangleMesh truth = test::cube();
  const PointCloud pc = test::sampled(truth, 40000, 5);
  const double diagonal = 2 * std::sqrt(3.0);
  double mean[3] = {}, worst[3] = {}, length[3] = {};
  size_t darts[3] = {}, corners[3] = {}, flips[3] = {};
  for (int now = 0; now < 3; ++now) {
    EncodeOptions o = test::crease_options(30, 1);
    if (now == 0) o.creases.valence_flips = o.creases.relax_beside_lines = false;
    o.creases.untag_flat = now == 2;
    // Against the baseline it was written for (no corner tags on flat
    // fans): with those tags on in both runs, this seed's level 1 is
    // 1.07e-5 without the flips and relaxation and 1.26e-5 with them.
    o.creases.flat_corners = false;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    darts[now] = enc.creases.darts, corners[now] = enc.creases.corners, flips[now] = enc.creases.align_valence_flips;
    auto t = build_topology(static_cast<uint32_t>(enc.control.vertex_count()), enc.control.triangles).value();
    for (uint32_t i = 0; i < t.edge_count(); ++i) {
      if (enc.contents.creases.empty() || !enc.contents.creases.edge[i]) continue;
      const float* pu = &enc.control.positions[3 * size_t{t.triangles[t.edge_half[i]]}];
      const float* pw = &enc.control.positions[3 * size_t{t.triangles[next_half(t.edge_half[i])]}];
      length[now] += std::sqrt(std::pow(pu[0] - pw[0], 2.0) + std::pow(pu[1] - pw[1], 2.0) + std::pow(pu[2] - pw[2], 2.0));
    }
    const TriangleMesh level{enc.levels.positions[1], enc.levels.triangles[1]};
    const MeshDistance d = mesh_distance(level, truth, {40000, 1, 2});
    mean[now] = d.mean() / diagonal, worst[now] = d.max() / diagonal;
  }
  // When written: level 1 2.44e-5 / 2.52% -> 1.26e-5 / 0.35% (132 flips);
  // tags 28.6 -> 24.4 long, 68 -> 37 darts, with untag_flat 22.5 and 24.
  CAPTURE(corners[0], corners[1], corners[2], mean[0], mean[1], mean[2], worst[0], worst[1], worst[2], length[0], length[1], length[2], darts[0], darts[1], darts[2], flips[1]);
  CHECK(flips[0] == 0);
  CHECK(flips[1] > 20);
  CHECK(mean[1] < 0.7 * mean[0]);
  CHECK(worst[1] < 0.01);
  // untag_flat: the cube's 12 edges are 24 units long.
  CHECK(length[2] < 1.1 * 24);
  CHECK(length[2] > 0.8 * 24);
  CHECK(darts[2] * 3 < darts[1] * 2);
}
