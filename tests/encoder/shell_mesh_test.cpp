// The shell triangulation on hand-built cell configurations: each of the
// paper's collapse types, and the checks every output passes.
#include <catch2/catch.hpp>

#include <array>
#include <initializer_list>
#include <map>

#include "dbss/decoder/topology.h"
#include "dbss/encoder/shell_mesh.h"

using namespace dbss;

namespace {
CellGrid cells(std::initializer_list<std::array<int, 3>> solid) {
  CellGrid g;
  g.n = {7, 7, 7};
  g.cell = 1;
  g.origin = {0, 0, 0};
  g.state.assign(7 * 7 * 7, CellGrid::kAir);
  for (const auto& c : solid) g.state[g.index(c[0] + 2, c[1] + 2, c[2] + 2)] = CellGrid::kOccupied;
  return g;
}

// Vertex valences of a closed mesh.
std::map<uint32_t, int> valences(const TriangleMesh& m) {
  std::map<uint32_t, int> v;
  for (uint32_t x : m.triangles) ++v[x];
  return v;
}
}  // namespace

TEST_CASE("a lone cell (Type 4 on all six faces) is a cube of 12 triangles") {
  const auto m = triangulate_shell(cells({{0, 0, 0}}));
  REQUIRE(m.ok());
  CHECK(m.value().vertex_count() == 8);
  CHECK(m.value().triangle_count() == 12);
  const MeshInfo i = mesh_info(m.value());
  CHECK(i.closed);
  CHECK(i.genus == 0);
}

TEST_CASE("Type 1: a cell with five air faces collapses its four air corners") {
  // Two cells stacked: each has five air faces and four corners no other
  // cell uses, which become one apex: an octahedron.
  const CellGrid g = cells({{0, 0, 0}, {0, 0, 1}});
  const auto plain = triangulate_shell(g, false);
  REQUIRE(plain.ok());
  CHECK(plain.value().vertex_count() == 12);
  CHECK(plain.value().triangle_count() == 20);
  const auto m = triangulate_shell(g);
  REQUIRE(m.ok());
  CHECK(m.value().vertex_count() == 6);
  CHECK(m.value().triangle_count() == 8);
  for (const auto& [v, n] : valences(m.value())) CHECK(n == 4);
}

TEST_CASE("Type 2: four air faces that are no ribbon collapse the two air corners") {
  // An L of three cells: the corner cell's solid faces are on two axes, and
  // the two corners on its outer edge are used by no other cell.
  const CellGrid g = cells({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const auto plain = triangulate_shell(g, false);
  const auto m = triangulate_shell(g);
  REQUIRE(plain.ok());
  REQUIRE(m.ok());
  // The arms are Type 1 (four corners each -> one), the corner cell Type 2
  // (two -> one): 16 corners become 16 - 3 - 3 - 1 = 9 vertices.
  CHECK(plain.value().vertex_count() == 16);
  CHECK(m.value().vertex_count() == 9);
  CHECK(mesh_info(m.value()).genus == 0);
  // A ribbon (a straight row's middle cell: solid faces on one axis) is not
  // collapsed: its four outer corners are shared with its neighbours anyway.
  const auto row = triangulate_shell(cells({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}));
  REQUIRE(row.ok());
  CHECK(row.value().vertex_count() == 2 + 8);  // two apexes, the two inner rings
}

TEST_CASE("Type 3: three air faces around one corner cut that corner off") {
  // A 2x2x2 block: every cell has three air faces around its outer corner,
  // whose quads are split so the corner keeps one triangle per face.
  const CellGrid g = cells({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}});
  const auto m = triangulate_shell(g);
  REQUIRE(m.ok());
  CHECK(m.value().vertex_count() == 26);
  CHECK(m.value().triangle_count() == 48);
  const auto plain = triangulate_shell(g, false);
  REQUIRE(plain.ok());
  // The block's 8 corners: valence 3 with the cut, more without it for some.
  int cut_corners = 0, plain_over3 = 0;
  for (const auto* mesh : {&m.value(), &plain.value()}) {
    const auto val = valences(*mesh);
    for (const auto& [v, n] : val) {
      const float* p = &mesh->positions[3 * size_t{v}];
      bool corner = true;
      for (int a = 0; a < 3; ++a) corner &= p[a] == 2.0f || p[a] == 4.0f;
      if (!corner) continue;
      if (mesh == &m.value()) cut_corners += n == 3;
      else plain_over3 += n > 3;
    }
  }
  CHECK(cut_corners == 8);
  CHECK(plain_over3 > 0);
}

TEST_CASE("every shell is a closed manifold with twice the solid's Euler characteristic") {
  // A ring of cells around a hole (genus 1, Euler 0: the rule holds for it
  // either way), and two separate blocks (Euler 2, shell 4: the factor shows).
  const CellGrid ring = cells({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}, {0, 2, 0}, {1, 2, 0}, {2, 2, 0}});
  CHECK(carving_shape(ring).euler == 0);
  for (bool collapse : {false, true}) {
    const auto m = triangulate_shell(ring, collapse);
    REQUIRE(m.ok());
    const MeshInfo i = mesh_info(m.value());
    CHECK(i.closed);
    CHECK(i.manifold);
    CHECK(i.genus == 1);
    CHECK(i.euler == 2 * carving_shape(ring).euler);
    auto t = build_topology(static_cast<uint32_t>(m.value().vertex_count()), m.value().triangles);
    CHECK(t.ok());  // consistently oriented, every vertex one fan
  }
  const CellGrid two = cells({{0, 0, 0}, {3, 3, 3}});
  CHECK(carving_shape(two).euler == 2);
  for (bool collapse : {false, true}) {
    const auto m = triangulate_shell(two, collapse);
    REQUIRE(m.ok());
    const MeshInfo i = mesh_info(m.value());
    CHECK(i.components == 2);
    CHECK(i.euler == 2 * carving_shape(two).euler);
  }
}
