#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "../sampled_shapes.h"
#include "../shapes.h"
#include "dbss/encoder/control_mesh.h"
#include "dbss/encoder/mesh_adjacency.h"
#include "dbss/encoder/mesh_folds.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/mesh_shape.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/self_intersections.h"

using namespace dbss;

namespace {

// Twice the signed area of triangle f seen from +z (the planar grid's
// triangles are counter-clockwise, positive).
double area_z(const TriangleMesh& m, size_t f) {
  const float* a = &m.positions[3 * size_t{m.triangles[3 * f]}];
  const float* b = &m.positions[3 * size_t{m.triangles[3 * f + 1]}];
  const float* c = &m.positions[3 * size_t{m.triangles[3 * f + 2]}];
  return double{b[0] - a[0]} * (c[1] - a[1]) - double{b[1] - a[1]} * (c[0] - a[0]);
}

// A flat grid whose vertex `c` was made the hub of a fan of slivers, as QEM
// leaves on a large flat face: each edge opposite c is flipped so that c
// gains it, while the two new triangles stay counter-clockwise (the
// triangulation stays a valid planar one), until c's valence reaches
// `valence`.
TriangleMesh sliver_fan(uint32_t c, uint32_t valence) {
  TriangleMesh m = test::planar_grid(12, 12);
  for (bool flipped = true; flipped;) {
    flipped = false;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> edge;
    for (uint32_t f = 0; f < m.triangle_count(); ++f)
      for (int k = 0; k < 3; ++k) edge[{m.triangles[3 * f + k], m.triangles[3 * f + (k + 1) % 3]}] = f;
    uint32_t count = 0;
    for (const auto& [uv, f] : edge) count += uv.first == c;
    if (count >= valence) break;
    for (uint32_t f = 0; f < m.triangle_count() && !flipped; ++f)
      for (int k = 0; k < 3 && !flipped; ++k) {
        if (m.triangles[3 * f + k] != c) continue;
        const uint32_t a = m.triangles[3 * f + (k + 1) % 3], b = m.triangles[3 * f + (k + 2) % 3];
        const auto twin = edge.find({b, a});
        if (twin == edge.end()) continue;
        const uint32_t g = twin->second;
        uint32_t d = 0;
        for (int j = 0; j < 3; ++j)
          if (m.triangles[3 * g + j] != a && m.triangles[3 * g + j] != b) d = m.triangles[3 * g + j];
        if (edge.count({c, d}) || edge.count({d, c})) continue;
        TriangleMesh t = m;
        const uint32_t t1[3] = {c, a, d}, t2[3] = {c, d, b};
        for (int j = 0; j < 3; ++j) t.triangles[3 * f + j] = t1[j], t.triangles[3 * g + j] = t2[j];
        if (area_z(t, f) > 1e-9 && area_z(t, g) > 1e-9) m = std::move(t), flipped = true;
      }
  }
  return m;
}

// Points on the grid's plane (z = 0), denser than its vertices.
PointCloud plane_points() {
  PointCloud pc;
  for (int j = 0; j <= 120; ++j)
    for (int i = 0; i <= 120; ++i) pc.xyz.insert(pc.xyz.end(), {0.1f * static_cast<float>(i) + 0.05f * (j % 2), 0.1f * j, 0.0f});
  return pc;
}

}  // namespace

TEST_CASE("triangle quality: 1 for an equilateral triangle, under 0.2 for a sliver, 0 for a degenerate one") {
  TriangleMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0.5f, static_cast<float>(std::sqrt(3.0) / 2), 0, 0.5f, 0.05f, 0, 2, 0, 0};
  m.triangles = {0, 1, 2, 0, 1, 3, 0, 1, 4};
  CHECK(triangle_quality(m, 0) == Approx(1.0).epsilon(1e-6));
  // base 1, height 0.05: 4*sqrt(3)*0.025 / (1 + 2 * 0.2525)
  CHECK(triangle_quality(m, 1) == Approx(4 * std::sqrt(3.0) * 0.025 / 1.505).epsilon(1e-5));
  CHECK(triangle_quality(m, 1) < kPoorQuality);
  CHECK(triangle_quality(m, 2) == 0);
  const MeshShape s = mesh_shape(m);
  CHECK(s.poor_share == Approx(2.0 / 3));
  CHECK(s.max_valence == 4);  // vertices 0 and 1 touch every other vertex
}

TEST_CASE("shaping mends a fan of slivers on a flat face: valence and quality, the plane, the boundary kept") {
  const uint32_t hub = 6 * 13 + 6;  // the middle of the 12 x 12 grid
  TriangleMesh m = sliver_fan(hub, 14);
  const MeshShape bad = mesh_shape(m);
  REQUIRE(bad.max_valence >= 14);
  REQUIRE(bad.poor_share > 0);  // two slivers of 288 triangles
  const MeshInfo info = mesh_info(m);
  const auto rim = rim_neighbours(m);
  const TriangleMesh before = m;
  const PointCloud pc = plane_points();
  const PointIndex index(pc);

  const ShapeStats st = improve_shape(m, &index);
  CHECK(st.before.max_valence == bad.max_valence);
  CHECK(st.flips > 0);
  CHECK(st.after.max_valence <= 8);
  CHECK(st.after.poor_share == 0);
  CHECK(st.after.min_quality > 2 * bad.min_quality);
  const MeshInfo now = mesh_info(m);
  CHECK(now.manifold);
  CHECK(now.euler == info.euler);
  CHECK(now.boundary_loops == info.boundary_loops);
  CHECK(m.triangle_count() == before.triangle_count());
  for (size_t f = 0; f < m.triangle_count(); ++f) CHECK(area_z(m, f) > 0);  // no triangle turned over
  CHECK(count_self_intersections(m) == 0);
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    CHECK(std::abs(m.positions[3 * v + 2]) < 1e-5f);  // on the points' plane
    if (rim[v][0] != kNotOnRim)                       // the boundary does not move
      for (int a = 0; a < 3; ++a) CHECK(m.positions[3 * v + a] == before.positions[3 * v + a]);
  }
  // Disabled, nothing changes; run again, next to nothing is left to do.
  TriangleMesh same = before;
  ShapeOptions off;
  off.enabled = false;
  improve_shape(same, &index, off);
  CHECK(same == before);
}

TEST_CASE("shaping never flips across a sharp edge: the fan folded by 90 degrees keeps its crease") {
  // The grid folded up along the row y = 9, away from the fan at y = 3: a
  // triangle with a vertex below the crease and one above it would cut the
  // corner.
  TriangleMesh m = sliver_fan(3 * 13 + 6, 16);
  for (size_t v = 0; v < m.vertex_count(); ++v)
    if (m.positions[3 * v + 1] > 9) m.positions[3 * v + 2] = m.positions[3 * v + 1] - 9, m.positions[3 * v + 1] = 9;
  const auto straddling = [](const TriangleMesh& t) {
    size_t n = 0;
    for (size_t f = 0; f < t.triangle_count(); ++f) {
      bool below = false, above = false;
      for (int k = 0; k < 3; ++k) {
        const float* p = &t.positions[3 * size_t{t.triangles[3 * f + k]}];
        below |= p[1] < 9 - 1e-4f;
        above |= p[2] > 1e-4f;
      }
      n += below && above;
    }
    return n;
  };
  REQUIRE(straddling(m) == 0);
  const TriangleMesh before = m;
  const ShapeStats st = improve_shape(m, nullptr);
  CHECK(st.flips > 0);
  CHECK(st.after.max_valence <= 8);
  CHECK(straddling(m) == 0);
  for (size_t v = 0; v < m.vertex_count(); ++v)
    if (before.positions[3 * v + 1] == 9)  // on the crease: stays
      for (int a = 0; a < 3; ++a) CHECK(m.positions[3 * v + a] == before.positions[3 * v + a]);
  CHECK(count_self_intersections(m) == 0);
}

TEST_CASE("control meshes of sampled shapes: shaped, valence at most 10, topology and crossings as before") {
  for (const test::Shape& s : test::genus_shapes()) {
    INFO(s.name);
    const PointCloud pc = test::sample_sdf(s.sdf, s.lo, s.hi, 20000);
    auto r = build_control_mesh(pc);
    REQUIRE(r.ok());
    const ControlMeshStages& st = r.value();
    const TriangleMesh& b = st.control;
    // QEM's mesh against the control mesh (shaped, then on the points).
    const MeshShape sa = mesh_shape(st.simplified), sb = mesh_shape(b);
    CHECK(st.shape_stats.before.poor_share == sa.poor_share);
    CHECK(st.shape_stats.after.poor_share == sb.poor_share);
    INFO("poor " << sa.poor_share << " -> " << sb.poor_share << ", max valence " << sa.max_valence << " -> " << sb.max_valence);
    // The cup's and the plate's creases bend by 90 degrees: no flip crosses
    // them and no vertex on them moves, and slivers along them stay
    // (issue 16's crease items).  Measured against QEM's mesh: cup 13.9% ->
    // 3.3%, max valence 14 -> 11; plate 17.3% -> 11.0%, 15 -> 9.  The smooth
    // shapes end at 0.2-0.75%, max valence 8-10 (QEM's: 0.2-0.9%, 10; the
    // jumps onto the points alone, unshaped, leave 0.7-2%).
    const bool creased = std::string(s.name) == "cup (U shape)" || std::string(s.name) == "thin plate";
    if (creased) {
      CHECK(sb.poor_share <= 0.7 * sa.poor_share);
      CHECK(sb.max_valence < sa.max_valence);
    } else {
      CHECK(sb.poor_share <= 0.01);
      CHECK(sb.max_valence <= 10);
    }
    const MeshInfo ia = mesh_info(st.simplified), ib = mesh_info(b);
    CHECK(ib.manifold);
    CHECK(ib.closed == ia.closed);
    CHECK(ib.genus == ia.genus);
    CHECK(ib.components == ia.components);
    CHECK(ib.boundary_loops == ia.boundary_loops);
    CHECK(b.triangle_count() == st.simplified.triangle_count());
    CHECK(count_self_intersections(b) == 0);
    CHECK(count_foldovers(b) == 0);
  }
}
