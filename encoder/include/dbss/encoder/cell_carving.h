// Cell carving (paper, section 3.1, Steps 1-5): a voxel grid around the
// points, empty cells carved away from the outside in through face
// neighbours; what stays is the solid whose outer faces become the shell.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "dbss/encoder/point_input.h"

namespace dbss {

struct CellGrid {
  // kInside: empty but not reachable from outside; kFilled: air made solid
  // to keep the shell manifold.
  enum State : uint8_t { kAir = 0, kOccupied = 1, kInside = 2, kFilled = 3 };
  std::array<int, 3> n{};            // cells per axis, two padding layers of air on every side included
  std::array<double, 3> origin{};    // corner of cell (0, 0, 0), model units
  double cell = 0;                   // cube side, model units
  std::vector<uint8_t> state;        // n[0] * n[1] * n[2], x fastest
  size_t index(int i, int j, int k) const { return (size_t(k) * n[1] + j) * n[0] + i; }
  bool solid(int i, int j, int k) const { return state[index(i, j, k)] != kAir; }
  size_t solid_count() const;
};

struct CarvingStats {
  int grid = 0;                 // cells along the longest side of the bounding box
  size_t occupied = 0;          // cells holding points
  size_t solid = 0;             // cells left after carving
  size_t repaired = 0;          // air cells filled to remove edge/vertex-only contacts
  double shift = 0;             // the cells' offset, in cells along each axis (0 or the search's 0.5)
};

// Carves a grid of `grid` cubic cells along the longest side of the points'
// bounding box.  Carving runs against the occupied cells closed
// morphologically (grown by one cell, carved, shrunk back by one cell), so it
// cannot leak through gaps of up to two cells in the sampling.  Afterwards the solid is made well-composed: wherever solid
// cells would meet only along an edge or at a corner (which makes the shell
// non-manifold), one of the air cells there is filled, and the carving is
// redone so no enclosed air remains.  grid in 2..1024.  shift (0 <= shift <
// 1) moves the cells by that share of a cell along every axis: the same
// grid falling differently on the points.
CellGrid carve(const PointCloud& points, int grid, CarvingStats* stats = nullptr, double shift = 0);

// What a carving says about the solid, to tell a closed carving from a leak.
struct CarvingShape {
  int64_t euler = 0;         // Euler characteristic of the solid cells' union: components - handles + cavities
  double inside_volume = 0;  // model units^3 of solid cells without points (the enclosed inside)
};
CarvingShape carving_shape(const CellGrid& g);

class PointIndex;

// The finest grid whose carving does not leak into the inside, and its
// carving as carve() makes it at stats.grid and stats.shift (the search
// carved it already): grids are stepped finer from cells of two point
// spacings until the enclosed volume collapses, the solid's topology tears
// or it needs patching; a grid that shows handles the choice before it did
// not is also carved half a cell moved, and the carving with fewer handles
// kept (see cell_carving.cpp); between 8 and max_grid.  `index` must be built on
// `points`.
struct CarvingChoice {
  CellGrid cells;
  CarvingStats stats;  // stats.grid is the chosen grid
  int leaking_grid = 0;  // the first of the leaking grids that ended the search (0: none leaked)
  // The search's evidence of a handle the choice closed (check_scan's
  // lost_handle): the choice's Euler characteristic, and the lowest one that
  // three consecutive grids coarser than the choice, none leaking, all show
  // (the highest of the three), or the choice's own when none is lower.
  // A handle the cells resolve at coarse grids and close at the choice is a
  // tube whose cut ends the coarse closing still bridged (both 0 when the
  // grid was given, not searched).
  int64_t euler = 0;
  int64_t coarser_euler = 0;
};
CarvingChoice choose_carving(const PointCloud& points, const PointIndex& index, int max_grid = 256);

// The grid search itself, on carvings `look` makes (choose_carving's: carve
// and carving_shape at that grid and shift; tests give scripted ones):
// grids in increasing order, each looked at unshifted, some also at shift
// 0.5, and grids past the last by next_search_grid when a handle must be
// seen to persist, none finer than `max_grid` (choose_carving's cap; a
// handle that would need one is not kept).  `look` may be called from two
// threads at once.
struct CarvingTrial {
  CarvingChoice carving;  // stats.grid, stats.shift, stats.repaired and stats.occupied are read
  CarvingShape shape;
};
using CarvingLook = std::function<CarvingTrial(int grid, double shift)>;
CarvingChoice search_carving_grids(const std::vector<int>& grids, const CarvingLook& look, int max_grid = 1024);
// The search's step: grid + grid / 12 (at least 1), at most `finest`.
int next_search_grid(int grid, int finest);

}  // namespace dbss
