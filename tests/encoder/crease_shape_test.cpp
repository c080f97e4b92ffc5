// The shaping pass on a tagged control mesh (crease_shape.h,
// CreaseOptions::shape_after_tags; issue 16 item 0: at most 1% of the
// control triangles under quality 0.2 and valence at most 10).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include "../crease_shapes.h"
#include "../sampled_shapes.h"
#include "../shapes.h"
#include "crease_shape.h"
#include "dbss/decoder/topology.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/mesh_folds.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/mesh_shape.h"
#include "encode_options.h"

using namespace dbss;
using test::Pairs;
using test::tagged_pairs;

namespace {

// A 15 x 15 grid in z = 0 (squares split along a diagonal, the vertices
// nudged off the lattice so that no three lie in line), then the edges
// opposite its middle vertex X flipped toward it until X has valence 18:
// a fan of slivers around one high-valence vertex, as QEM leaves on a flat
// face.  The row j = 3 is a tagged line (its edges tagged, its vertices
// counted), and (3, 3) a corner.
constexpr uint32_t kN = 15;
constexpr uint32_t id(uint32_t i, uint32_t j) { return kN * j + i; }
constexpr uint32_t kX = id(7, 7);
constexpr uint32_t kLine = 3;

double orient(const TriangleMesh& m, uint32_t a, uint32_t b, uint32_t c) {
  const float* p = &m.positions[3 * size_t{a}];
  const float* q = &m.positions[3 * size_t{b}];
  const float* r = &m.positions[3 * size_t{c}];
  return double{q[0] - p[0]} * (r[1] - p[1]) - double{q[1] - p[1]} * (r[0] - p[0]);
}

uint32_t valence(const TriangleMesh& m, uint32_t v) {
  std::set<uint32_t> ring;
  for (size_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k)
      if (m.triangles[3 * f + k] == v) ring.insert(m.triangles[3 * f + (k + 1) % 3]), ring.insert(m.triangles[3 * f + (k + 2) % 3]);
  return static_cast<uint32_t>(ring.size());
}

TriangleMesh spiked_grid() {
  TriangleMesh m;
  for (uint32_t j = 0; j < kN; ++j)
    for (uint32_t i = 0; i < kN; ++i) {
      const float dx = 0.11f * std::sin(1.7f * float(i) + 2.3f * float(j)), dy = 0.11f * std::cos(2.9f * float(i) + 1.3f * float(j));
      m.positions.insert(m.positions.end(), {float(i) + (j == kLine ? 0 : dx), float(j) + (j == kLine ? 0 : dy), 0});
    }
  for (uint32_t j = 0; j + 1 < kN; ++j)
    for (uint32_t i = 0; i + 1 < kN; ++i) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  // Flip the edge opposite X in one of X's triangles while X's valence is
  // under 18 and some flip keeps both new triangles turned the right way.
  for (bool flipped = true; flipped && valence(m, kX) < 18;) {
    flipped = false;
    for (size_t f = 0; f < m.triangle_count() && !flipped; ++f) {
      uint32_t* t = &m.triangles[3 * f];
      int k = 0;
      while (k < 3 && t[k] != kX) ++k;
      if (k == 3) continue;
      const uint32_t a = t[(k + 1) % 3], b = t[(k + 2) % 3];
      for (size_t g = 0; g < m.triangle_count() && !flipped; ++g) {
        uint32_t* s = &m.triangles[3 * g];
        for (int l = 0; l < 3 && !flipped; ++l) {
          if (s[l] != b || s[(l + 1) % 3] != a) continue;
          const uint32_t d = s[(l + 2) % 3];
          if (valence(m, d) <= 3 || orient(m, kX, a, d) <= 0 || orient(m, kX, d, b) <= 0) continue;
          bool exists = false;
          for (size_t h = 0; h < m.triangle_count() && !exists; ++h) {
            const uint32_t* r = &m.triangles[3 * h];
            exists = (r[0] == kX || r[1] == kX || r[2] == kX) && (r[0] == d || r[1] == d || r[2] == d);
          }
          if (exists) continue;
          t[0] = kX, t[1] = a, t[2] = d;
          s[0] = kX, s[1] = d, s[2] = b;
          flipped = true;
        }
      }
    }
  }
  return m;
}

// Points on the plane z = 0 over the grid, 10 a unit.
PointCloud plane_points() {
  PointCloud pc;
  for (int j = -5; j <= 10 * int(kN - 1) + 5; ++j)
    for (int i = -5; i <= 10 * int(kN - 1) + 5; ++i) pc.xyz.insert(pc.xyz.end(), {0.1f * float(i), 0.1f * float(j), 0});
  return pc;
}

EncodeOptions command_options(uint32_t levels) {
  EncodeOptions o;
  tools::set_command_defaults(o);
  o.levels = levels;
  o.threads = 2;
  return o;
}

}  // namespace

TEST_CASE("shaping a tagged mesh takes a valence-18 vertex and its slivers down and leaves the line and the corner as they were") {
  TriangleMesh m = spiked_grid();
  REQUIRE(valence(m, kX) == 18);
  auto built = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
  REQUIRE(built.ok());
  const LevelTopology& t = built.value();
  format::Creases tags;
  tags.edge.assign(t.edge_count(), 0);
  tags.corner.assign(t.vertex_count, 0);
  std::vector<uint32_t> count(t.vertex_count, 0);
  Pairs line;
  for (uint32_t i = 0; i + 1 < kN; ++i) line.insert({id(i, kLine), id(i + 1, kLine)});
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t u = t.triangles[t.edge_half[e]], w = t.triangles[next_half(t.edge_half[e])];
    if (line.count({std::min(u, w), std::max(u, w)})) tags.edge[e] = 1, ++count[u], ++count[w];
  }
  tags.corner[id(3, kLine)] = 1;
  const TriangleMesh before = m;
  const MeshShape was = mesh_shape(m);
  const MeshInfo info = mesh_info(m);
  INFO("before: " << 100 * was.poor_share << "% poor, max valence " << was.max_valence);
  REQUIRE(was.max_valence == 18);
  REQUIRE(was.poor_share > 0.01);

  const PointCloud cloud = plane_points();
  const PointIndex points(cloud);
  LevelTopology shaped;
  const std::vector<uint32_t> counted = count;
  const ShapeStats st = shape_tagged_mesh(m, t, tags, count, points, shaped);
  const MeshShape now = mesh_shape(m);
  INFO("after: " << 100 * now.poor_share << "% poor, max valence " << now.max_valence << "; " << st.flips << " flips, " << st.moves << " moves");
  CHECK(st.flips > 0);
  CHECK(now.poor_share <= 0.01);
  CHECK(now.max_valence <= 10);
  // The same surface: topology, boundary, no fold, every vertex in z = 0.
  const MeshInfo after = mesh_info(m);
  CHECK(after.manifold);
  CHECK(after.euler == info.euler);
  CHECK(after.boundary_loops == info.boundary_loops);
  CHECK(after.components == info.components);
  CHECK(m.triangle_count() == before.triangle_count());
  CHECK(count_foldovers(m, 90) == 0);
  for (size_t f = 0; f < m.triangle_count(); ++f) CHECK(orient(m, m.triangles[3 * f], m.triangles[3 * f + 1], m.triangles[3 * f + 2]) > 0);
  for (size_t v = 0; v < m.vertex_count(); ++v) CHECK(m.positions[3 * v + 2] == 0);
  // The line: its tags on the same edges (in the new edge order), its
  // vertices and the corner where they were, the counts unchanged.
  const LevelTopology& final_t = st.flips > 0 ? shaped : t;
  CHECK(tagged_pairs(final_t, tags) == line);
  CHECK(count == counted);
  CHECK(tags.corner[id(3, kLine)] == 1);
  for (uint32_t i = 0; i < kN; ++i)
    for (int a = 0; a < 3; ++a) CHECK(m.positions[3 * size_t{id(i, kLine)} + a] == before.positions[3 * size_t{id(i, kLine)} + a]);
}

TEST_CASE("a sampled cube under the default options: at most 1% of its control triangles under quality 0.2 and valence at most 10") {
  const TriangleMesh cube = test::cube();
  for (uint32_t seed : {1u, 2u}) {
    INFO("seed " << seed);
    auto e = encode_points(test::sampled(cube, 40000, seed), command_options(1));
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    REQUIRE(!enc.contents.creases.empty());
    const MeshShape s = mesh_shape(enc.control);
    CAPTURE(s.poor_share, s.max_valence, enc.creases.shape_flips, enc.creases.shape_moves);
    CHECK(s.poor_share <= 0.01);
    CHECK(s.max_valence <= 10);
    if (seed == 1) {
      // Without the pass the same cloud misses the bounds (crease_bench,
      // seed 1: 0.93% and valence 11).
      EncodeOptions off = command_options(1);
      off.creases.shape_after_tags = false;
      auto unshaped = encode_points(test::sampled(cube, 40000, seed), off);
      REQUIRE(unshaped.ok());
      const MeshShape u = mesh_shape(unshaped.value().control);
      CAPTURE(u.poor_share, u.max_valence);
      CHECK((u.poor_share > 0.01 || u.max_valence > 10));
    }
  }
}

TEST_CASE("shaping a tagged mesh flips nothing at a vertex of an untagged sharp edge") {
  // The spiked grid folded by 90 degrees along x = 7 (x > 7 goes up the
  // wall x = 7), untagged: X (valence 18, its slivers on both sides) sits
  // on the fold, a feature the tags missed (a gap in a line).  Its fan must
  // stay as it is (ShapeLocks::beside 2); without that lock the flips on
  // the flat side take its valence down.
  TriangleMesh m = spiked_grid();
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    float* p = &m.positions[3 * v];
    if (p[0] > 7) p[2] = p[0] - 7, p[0] = 7;
  }
  REQUIRE(valence(m, kX) == 18);
  auto built = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
  REQUIRE(built.ok());
  const LevelTopology& t = built.value();
  format::Creases tags;
  tags.edge.assign(t.edge_count(), 0);
  tags.corner.assign(t.vertex_count, 0);
  const std::vector<uint32_t> count(t.vertex_count, 0);
  PointCloud cloud;
  for (int j = -5; j <= 10 * int(kN - 1) + 5; ++j) {
    for (int i = -5; i <= 70; ++i) cloud.xyz.insert(cloud.xyz.end(), {0.1f * float(i), 0.1f * float(j), 0});
    for (int k = 1; k <= 10 * int(kN - 8) + 5; ++k) cloud.xyz.insert(cloud.xyz.end(), {7, 0.1f * float(j), 0.1f * float(k)});
  }
  const PointIndex points(cloud);
  std::multiset<std::vector<uint32_t>> fan_before;
  const auto fan = [&](const TriangleMesh& mesh) {
    std::multiset<std::vector<uint32_t>> out;
    for (size_t f = 0; f < mesh.triangle_count(); ++f) {
      std::vector<uint32_t> tri(mesh.triangles.begin() + 3 * f, mesh.triangles.begin() + 3 * f + 3);
      if (std::find(tri.begin(), tri.end(), kX) == tri.end()) continue;
      std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
      out.insert(tri);
    }
    return out;
  };
  fan_before = fan(m);
  LevelTopology shaped;
  const ShapeStats st = shape_tagged_mesh(m, t, tags, count, points, shaped);
  INFO(st.flips << " flips, " << st.moves << " moves");
  CHECK(valence(m, kX) == 18);
  CHECK(fan(m) == fan_before);
}
