// Cell carving on hand-made occupancy: every point sits at the centre of one
// cell of a unit lattice, so the occupied cells are exactly the ones listed
// and the carving's result can be worked out by hand (closing by one cell,
// carving through face neighbours, giving one layer back, see
// cell_carving.h).
#include <catch2/catch.hpp>

#include <array>
#include <set>

#include "dbss/encoder/cell_carving.h"

using namespace dbss;

namespace {

using Cell = std::array<int, 3>;

// Points at the centres of `cells` on a lattice of unit cubes, plus the two
// corners of the lattice box [0, size] (which must lie in occupied corner
// cells, so they add none): the carving's bounding box is then exactly the
// box, its cells are the lattice cells (offset by two padding cells) at
// `grid` = the longest side, and each centre point occupies one cell only.
PointCloud lattice_points(const std::set<Cell>& cells, const Cell& size) {
  REQUIRE(cells.count({0, 0, 0}));
  REQUIRE(cells.count({size[0] - 1, size[1] - 1, size[2] - 1}));
  PointCloud pc;
  for (const Cell& c : cells)
    pc.xyz.insert(pc.xyz.end(), {c[0] + 0.5f, c[1] + 0.5f, c[2] + 0.5f});
  pc.xyz.insert(pc.xyz.end(), {0.0f, 0.0f, 0.0f});
  pc.xyz.insert(pc.xyz.end(), {float(size[0]), float(size[1]), float(size[2])});
  return pc;
}

struct Carved {
  CellGrid grid;
  CarvingStats stats;
  CarvingShape shape;
};

Carved carve_cells(const std::set<Cell>& cells, const Cell& size) {
  Carved c;
  c.grid = carve(lattice_points(cells, size), std::max({size[0], size[1], size[2]}), &c.stats);
  c.shape = carving_shape(c.grid);
  REQUIRE(c.grid.cell == 1.0);
  REQUIRE(c.stats.occupied == cells.size());
  return c;
}

bool solid_at(const CellGrid& g, const Cell& c) { return g.solid(c[0] + 2, c[1] + 2, c[2] + 2); }

// The faces of the box [0, n)^3 one cell thick.
std::set<Cell> hollow_box(const Cell& n) {
  std::set<Cell> s;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        if (i == 0 || j == 0 || k == 0 || i == n[0] - 1 || j == n[1] - 1 || k == n[2] - 1) s.insert({i, j, k});
  return s;
}

}  // namespace

TEST_CASE("carving a closed box with walls one cell thick keeps the whole box") {
  // 6x6x6 box, 152 wall cells: the 4x4x4 inside cannot be reached through
  // face neighbours, so it stays (64 cells of enclosed inside); nothing
  // outside the walls is solid.
  const Cell n{6, 6, 6};
  const Carved c = carve_cells(hollow_box(n), n);
  CHECK(c.stats.occupied == 152);
  CHECK(c.stats.solid == 216);
  CHECK(c.stats.repaired == 0);
  CHECK(c.shape.euler == 1);  // one ball: genus 0, no cavity
  CHECK(c.shape.inside_volume == 64.0);
  for (int k = -2; k < 8; ++k)
    for (int j = -2; j < 8; ++j)
      for (int i = -2; i < 8; ++i) {
        const bool in_box = i >= 0 && j >= 0 && k >= 0 && i < 6 && j < 6 && k < 6;
        CHECK(solid_at(c.grid, {i, j, k}) == in_box);
      }
}

TEST_CASE("walls whose cells touch only along edges, and slits two cells wide, still close the box") {
  // A checkerboard wall (cells meeting only along edges) on the x = 0 face
  // and a 2x2 slit in the x = 5 face: the closing bridges both, the whole
  // 6x6x6 box stays solid.
  const Cell n{6, 6, 6};
  std::set<Cell> cells = hollow_box(n);
  for (int k = 1; k < 5; ++k)
    for (int j = 1; j < 5; ++j)
      if ((j + k) % 2) cells.erase({0, j, k});
  for (int k = 2; k < 4; ++k)
    for (int j = 2; j < 4; ++j) cells.erase({5, j, k});
  const Carved c = carve_cells(cells, n);
  CHECK(c.stats.occupied == 152 - 8 - 4);
  CHECK(c.stats.solid == 216);
  CHECK(c.stats.repaired == 0);
  CHECK(c.shape.euler == 1);
}

TEST_CASE("an open square tube with walls one cell thick is carved to the tube itself, genus 1") {
  // Walls of a 5x5 section, 7 cells long, open at both ends: the inside is
  // carved from the ends (every inside cell touches the carved centre line),
  // so only the 16 x 7 wall cells stay, a solid ring.
  std::set<Cell> cells;
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        if (i == 0 || j == 0 || i == 4 || j == 4) cells.insert({i, j, k});
  const Carved c = carve_cells(cells, {5, 5, 7});
  CHECK(c.stats.occupied == 112);
  CHECK(c.stats.solid == 112);
  CHECK(c.stats.repaired == 0);
  CHECK(c.shape.euler == 0);  // one handle
  CHECK(c.shape.inside_volume == 0.0);
}

TEST_CASE("carving does not pass a gap that is open only diagonally") {
  // A 12x7x7 box whose two x faces are double walls: layers at x = 0 and
  // x = 3 (and at x = 11 and x = 8), each with a 3x3 hole, the inner hole
  // shifted by one cell in y and z against the outer one.  After the
  // closing, the air in each outer hole reaches x = 1 at the hole's centre
  // (2, 2) and the inner hole's air starts at x = 2 at (3, 3): the two touch
  // only at a corner.  Carving through face neighbours stops there, so the
  // inside stays; giving back one layer opens a 3x3x3 dent behind each outer
  // hole (x = 0..2, y and z = 1..3, and the mirror at x = 9..11).
  // Solid: 12 * 7 * 7 - 2 * 27 = 534 cells, one ball (euler 1).  Carving
  // through the corner (26 neighbours) hollows the box into a shell with a
  // tunnel through it: 396 cells, euler 0.
  const Cell n{12, 7, 7};
  std::set<Cell> cells = hollow_box(n);
  for (int k = 1; k < 6; ++k)
    for (int j = 1; j < 6; ++j) cells.insert({3, j, k}), cells.insert({8, j, k});
  for (int k = 1; k <= 3; ++k)
    for (int j = 1; j <= 3; ++j) cells.erase({0, j, k}), cells.erase({11, j, k});
  for (int k = 2; k <= 4; ++k)
    for (int j = 2; j <= 4; ++j) cells.erase({3, j, k}), cells.erase({8, j, k});
  const Carved c = carve_cells(cells, n);
  CHECK(c.stats.occupied == 338 + 2 * 25 - 4 * 9);
  CHECK(c.stats.solid == 534);
  CHECK(c.stats.repaired == 0);
  CHECK(c.shape.euler == 1);
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 12; ++i) {
        const bool dent = (i <= 2 || i >= 9) && j >= 1 && j <= 3 && k >= 1 && k <= 3;
        CHECK(solid_at(c.grid, {i, j, k}) == !dent);
      }
}
