// The tagged control mesh's clean-up after the crease tags are chosen
// (creases.cpp): slivers along a tagged line flipped away
// (crease_slivers.h), short untagged edges under long rings collapsed
// (crease_short_edges.h).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "crease_short_edges.h"
#include "crease_slivers.h"
#include "../crease_shapes.h"
#include "dbss/decoder/topology.h"

using namespace dbss;
using test::Pairs;
using test::tagged_pairs;

namespace {

bool has_edge(const LevelTopology& t, uint32_t a, uint32_t b) {
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t u = t.triangles[t.edge_half[e]], w = t.triangles[next_half(t.edge_half[e])];
    if ((u == a && w == b) || (u == b && w == a)) return true;
  }
  return false;
}

// A fold along the x axis: face A in z = 0 (y > 0), face B below the line;
// the line's edge u-w (vertices 0-1) is tagged, and c (2) sits `apex` off
// it on face A.  Vertices: u 0, w 1, c 2, a1 3, a2 4, d 5.
TriangleMesh fold(float apex) {
  TriangleMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0.5f, apex, 0, 0, 1, 0, 1, 1, 0, 0.5f, 0, -1};
  m.triangles = {0, 1, 2, 2, 1, 4, 2, 4, 3, 0, 2, 3, 1, 0, 5};
  return m;
}

format::Creases tag_pairs(const LevelTopology& t, const Pairs& pairs) {
  format::Creases tags;
  tags.edge.assign(t.edge_count(), 0);
  tags.corner.assign(t.vertex_count, 0);
  for (uint32_t e = 0; e < t.edge_count(); ++e) {
    const uint32_t u = t.triangles[t.edge_half[e]], w = t.triangles[next_half(t.edge_half[e])];
    tags.edge[e] = pairs.count({std::min(u, w), std::max(u, w)}) ? 1 : 0;
  }
  return tags;
}

// A 7 x 7 grid in z = 0, each square split along its rising diagonal, with
// the interior vertex (3, 3) slid to 0.05 from its right neighbour (4, 3).
constexpr uint32_t id(uint32_t i, uint32_t j) { return 7 * j + i; }
TriangleMesh grid_with_short_edge() {
  TriangleMesh m;
  for (uint32_t j = 0; j < 7; ++j)
    for (uint32_t i = 0; i < 7; ++i) m.positions.insert(m.positions.end(), {float(i), float(j), 0});
  for (uint32_t j = 0; j < 6; ++j)
    for (uint32_t i = 0; i < 6; ++i) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m.positions[3 * id(3, 3)] = 3.95f;
  return m;
}

}  // namespace

TEST_CASE("a sliver whose corner lies on a tagged edge is flipped and the tag follows the line through it") {
  TriangleMesh m = fold(0.01f);
  const LevelTopology t = build_topology(6, m.triangles).value();
  format::Creases tags = tag_pairs(t, {{0, 1}});
  std::vector<uint32_t> count = {1, 1, 0, 0, 0, 0};
  LevelTopology flipped;
  REQUIRE(flip_slivers(m, t, tags, count, flipped) == 1);
  CHECK(!has_edge(flipped, 0, 1));
  CHECK(has_edge(flipped, 2, 5));
  CHECK(tagged_pairs(flipped, tags) == Pairs{{0, 2}, {1, 2}});
  CHECK(count[2] == 2);
  CHECK(m.positions[3 * 2 + 1] == 0.0f);  // c moved onto the line
  // Face B's two triangles now: both at d, both turned as (w, u, d) was
  // (normal towards -y).
  int below = 0;
  for (uint32_t f = 0; f < flipped.triangle_count(); ++f) {
    const uint32_t* c = &flipped.triangles[3 * f];
    if (c[0] != 5 && c[1] != 5 && c[2] != 5) continue;
    ++below;
    const float* p = m.positions.data();
    const double ax = p[3 * c[1]] - p[3 * c[0]], az = p[3 * c[1] + 2] - p[3 * c[0] + 2];
    const double bx = p[3 * c[2]] - p[3 * c[0]], bz = p[3 * c[2] + 2] - p[3 * c[0] + 2];
    CHECK(az * bx - ax * bz < 0);  // the normal's y component
  }
  CHECK(below == 2);
}

TEST_CASE("a tagged edge whose triangle's corner is well off its line is not flipped") {
  TriangleMesh m = fold(0.3f);
  const TriangleMesh before = m;
  const LevelTopology t = build_topology(6, m.triangles).value();
  format::Creases tags = tag_pairs(t, {{0, 1}});
  std::vector<uint32_t> count = {1, 1, 0, 0, 0, 0};
  LevelTopology flipped;
  CHECK(flip_slivers(m, t, tags, count, flipped) == 0);
  CHECK(m.triangles == before.triangles);
  CHECK(m.positions == before.positions);
}

TEST_CASE("a short untagged edge under long rings is collapsed and no triangle turns over") {
  TriangleMesh m = grid_with_short_edge();
  const LevelTopology t = build_topology(49, m.triangles).value();
  format::Creases tags = tag_pairs(t, {});
  std::vector<uint32_t> count(49, 0);
  LevelTopology collapsed;
  REQUIRE(collapse_short_edges(m, t, tags, count, collapsed) == 1);
  CHECK(m.vertex_count() == 48);
  CHECK(m.triangle_count() == 70);
  CHECK(collapsed.vertex_count == 48);
  CHECK(tags.corner.size() == 48);
  CHECK(tags.edge.size() == collapsed.edge_count());
  double shortest = INFINITY;
  const float* p = m.positions.data();
  for (uint32_t f = 0; f < m.triangle_count(); ++f) {
    const uint32_t* c = &m.triangles[3 * f];
    const double ax = p[3 * c[1]] - p[3 * c[0]], ay = p[3 * c[1] + 1] - p[3 * c[0] + 1];
    const double bx = p[3 * c[2]] - p[3 * c[0]], by = p[3 * c[2] + 1] - p[3 * c[0] + 1];
    CHECK(ax * by - ay * bx > 0);
    for (int k = 0; k < 3; ++k) {
      const uint32_t u = c[k], w = c[(k + 1) % 3];
      shortest = std::min(shortest, std::hypot(double{p[3 * u]} - p[3 * w], double{p[3 * u + 1]} - p[3 * w + 1]));
    }
  }
  CHECK(shortest > 0.5);
}

TEST_CASE("a short edge at a tagged vertex keeps the tagged vertex where it is and its tags") {
  TriangleMesh m = grid_with_short_edge();
  const LevelTopology t = build_topology(49, m.triangles).value();
  // The line x = 4 tagged through (4, 3), the short edge's right end.
  format::Creases tags = tag_pairs(t, {{id(4, 2), id(4, 3)}, {id(4, 3), id(4, 4)}});
  std::vector<uint32_t> count(49, 0);
  count[id(4, 2)] = count[id(4, 4)] = 1, count[id(4, 3)] = 2;
  const float kept[2] = {m.positions[3 * id(4, 3)], m.positions[3 * id(4, 3) + 1]};
  LevelTopology collapsed;
  REQUIRE(collapse_short_edges(m, t, tags, count, collapsed) == 1);
  // (3, 3) = 24 went; (4, 3) = 25 is now 24, where it was, and (4, 4) = 32 is 31.
  CHECK(m.positions[3 * 24] == kept[0]);
  CHECK(m.positions[3 * 24 + 1] == kept[1]);
  CHECK(count[24] == 2);
  CHECK(tagged_pairs(collapsed, tags) == Pairs{{id(4, 2), 24}, {24, 31}});
}

TEST_CASE("a short edge between two tagged vertices is left alone") {
  TriangleMesh m = grid_with_short_edge();
  const TriangleMesh before = m;
  const LevelTopology t = build_topology(49, m.triangles).value();
  format::Creases tags = tag_pairs(t, {{id(3, 3), id(3, 4)}, {id(4, 3), id(4, 4)}});
  std::vector<uint32_t> count(49, 0);
  count[id(3, 3)] = count[id(3, 4)] = count[id(4, 3)] = count[id(4, 4)] = 1;
  LevelTopology collapsed;
  CHECK(collapse_short_edges(m, t, tags, count, collapsed) == 0);
  CHECK(m.triangles == before.triangles);
}
