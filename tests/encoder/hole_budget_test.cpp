// The control budget per hole (hole_budget.h): the loops found, the rim
// vertices a loop's curve needs, and the faces given for them.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "../shapes.h"
#include "dbss/encoder/hole_budget.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/mesh_input.h"
#include "dbss/encoder/open_surface.h"
#include "dbss/encoder/simplify.h"

using namespace dbss;

namespace {

// A UV sphere with the star of each vertex in `holes` (ring, side) removed.
TriangleMesh sphere_with_holes(uint32_t rings, uint32_t sides, const std::vector<std::pair<uint32_t, uint32_t>>& holes,
                               uint32_t radius = 0) {
  TriangleMesh s = test::uv_sphere(rings, sides);
  std::vector<uint8_t> gone(s.vertex_count(), 0);
  for (auto [i, j] : holes)
    for (uint32_t di = i - radius; di <= i + radius; ++di)
      for (uint32_t dj = j + sides - radius; dj <= j + sides + radius; ++dj) gone[di * sides + dj % sides] = 1;
  return prepare_mesh_input(test::without_stars(s, gone)).value();
}

// A closed polyline: a circle of radius 1 with n vertices.
std::vector<float> circle(uint32_t n) {
  std::vector<float> p;
  for (uint32_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    p.insert(p.end(), {static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f});
  }
  return p;
}

}  // namespace

TEST_CASE("hole budget: boundary loops are the mesh's, each a closed walk", "[hole_budget]") {
  const TriangleMesh m = sphere_with_holes(24, 32, {{6, 3}, {12, 10}, {18, 20}}, 1);
  const MeshInfo info = mesh_counts(m);
  const auto loops = boundary_loops(m);
  REQUIRE(loops.size() == info.boundary_loops);
  REQUIRE(loops.size() == 3);
  for (const auto& loop : loops) {
    // The star of a 3x3 block of vertices of the grid (split by one
    // diagonal per quad) leaves a loop of 14 edges.
    CHECK(loop.size() == 14);
    std::vector<uint32_t> sorted = loop;
    std::sort(sorted.begin(), sorted.end());
    CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
  }
  CHECK(boundary_loops(test::uv_sphere(12, 16)).empty());
}

TEST_CASE("hole budget: a loop needs the vertices its curve's sagitta asks for", "[hole_budget]") {
  const std::vector<float> p = circle(256);
  std::vector<uint32_t> loop(256);
  for (uint32_t i = 0; i < 256; ++i) loop[i] = i;
  // A chord over an angle a strays 1 - cos(a / 2) from the circle: at most
  // 0.01 needs 23 chords or more; Douglas-Peucker keeps at most twice the
  // fewest (it halves ranges).
  const uint32_t fine = loop_vertices_needed(p, loop, 0.01);
  CHECK(fine >= 23);
  CHECK(fine <= 64);
  const uint32_t coarse = loop_vertices_needed(p, loop, 0.2);
  CHECK(coarse >= 4);  // 1 - cos(pi / 4) = 0.29 > 0.2 for a square
  CHECK(coarse < fine);
  // Douglas-Peucker starts from a diameter, so a tolerance a triangle
  // would meet (its sagitta is 0.5) still keeps four; past the radius,
  // the diameter itself is enough and the floor of three holds.
  CHECK(loop_vertices_needed(p, loop, 0.6) == 4);
  CHECK(loop_vertices_needed(p, loop, 1.01) == 3);
  CHECK(loop_vertices_needed(p, {0, 1, 2}, 1e-6) == 3);
}

TEST_CASE("hole budget: closed meshes keep the closed budget, holes add faces by their curve", "[hole_budget]") {
  const TriangleMesh closed = test::uv_sphere(24, 32);
  const HoleBudget c = hole_budget(closed, 0);
  CHECK(c.faces == default_control_faces(static_cast<uint32_t>(closed.triangle_count()), 0));
  CHECK(c.loop_vertices.empty());
  // A big hole (the stars of a 7x7 block) needs more rim vertices than a
  // small one (one vertex's star): the budget is not a count of loops.
  const TriangleMesh small = sphere_with_holes(24, 32, {{12, 10}}, 0);
  const TriangleMesh big = sphere_with_holes(24, 32, {{12, 10}}, 3);
  const HoleBudget s = hole_budget(small, 0), b = hole_budget(big, 0);
  REQUIRE(s.loop_vertices.size() == 1);
  REQUIRE(b.loop_vertices.size() == 1);
  CHECK(s.loop_vertices[0] <= 5);
  CHECK(b.loop_vertices[0] > s.loop_vertices[0]);
  CHECK(b.faces > s.faces);
  CHECK(s.faces >= s.closed_faces + static_cast<uint32_t>(kHoleFacesPerVertex * 3));
}

TEST_CASE("hole budget: many tiny holes ask for at most three quarters of the input's triangles", "[hole_budget]") {
  // Every third vertex of every third ring holed (stars apart, so the mesh
  // stays manifold): a raw scan's pinholes.  Uncapped, 11 faces per hole
  // would ask for more faces than the mesh has.
  std::vector<std::pair<uint32_t, uint32_t>> holes;
  for (uint32_t i = 2; i < 11; i += 3)
    for (uint32_t j = 0; j + 3 < 16; j += 3) holes.emplace_back(i, j);
  const TriangleMesh m = sphere_with_holes(12, 16, holes, 0);
  // 20 faces per rim vertex (the default is 3) so that this small mesh's
  // holes ask for more than it has.
  const double per_vertex = 20;
  const HoleBudget b = hole_budget(m, 0, kHoleTolerance, per_vertex);
  REQUIRE(b.loop_vertices.size() == holes.size());
  const double uncapped = b.closed_faces + static_cast<double>(holes.size()) * (per_vertex * 3 + 2);
  REQUIRE(uncapped > static_cast<double>(m.triangle_count()));
  CHECK(b.faces <= 0.75 * static_cast<double>(m.triangle_count()));
  CHECK(b.faces >= b.closed_faces);
}
