#include "dbss/encoder/cell_carving.h"

#include <algorithm>
#include <cmath>

#include "dbss/encoder/point_index.h"

namespace dbss {

size_t CellGrid::solid_count() const {
  return static_cast<size_t>(std::count_if(state.begin(), state.end(), [](uint8_t s) { return s != kAir; }));
}

namespace {

CellGrid make_grid(const PointCloud& pc, int grid) {
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < pc.size(); ++i)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double{pc.xyz[3 * i + a]}), hi[a] = std::max(hi[a], double{pc.xyz[3 * i + a]});
  const double longest = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  CellGrid g;
  g.cell = longest / grid;
  for (int a = 0; a < 3; ++a) {
    const int cells = std::max(1, static_cast<int>(std::ceil((hi[a] - lo[a]) / g.cell - 1e-9)));
    // Two cells of padding: the closing grows the occupied cells by one, and
    // one layer of air must still surround everything.
    g.n[a] = cells + 4;
    // Centre the points in the cells of this axis, then pad.
    g.origin[a] = lo[a] - 0.5 * (cells * g.cell - (hi[a] - lo[a])) - 2 * g.cell;
  }
  g.state.assign(size_t(g.n[0]) * g.n[1] * g.n[2], CellGrid::kInside);
  // A cell is occupied if a point lies within kReach cells of it (in each
  // axis), not only inside it: sampled surfaces pass between cells that touch
  // only along an edge or at a corner, and the face-neighbour carving would
  // leak through those contacts.  The thin margin makes the occupied band
  // tight against 6-connected carving wherever the sampling is dense.
  constexpr double kReach = 0.3;
  for (size_t i = 0; i < pc.size(); ++i) {
    int lo_c[3], hi_c[3];
    for (int a = 0; a < 3; ++a) {
      const double u = (pc.xyz[3 * i + a] - g.origin[a]) / g.cell;
      lo_c[a] = std::clamp(static_cast<int>(std::floor(u - kReach)), 2, g.n[a] - 3);
      hi_c[a] = std::clamp(static_cast<int>(std::floor(u + kReach)), 2, g.n[a] - 3);
    }
    for (int k = lo_c[2]; k <= hi_c[2]; ++k)
      for (int j = lo_c[1]; j <= hi_c[1]; ++j)
        for (int c = lo_c[0]; c <= hi_c[0]; ++c) g.state[g.index(c, j, k)] = CellGrid::kOccupied;
  }
  return g;
}

// Breadth-first from every border cell through face neighbours whose state
// `passable` accepts; returns which cells were reached.
template <class Passable>
std::vector<uint8_t> flood_from_border(const CellGrid& g, Passable passable) {
  std::vector<uint8_t> seen(g.state.size(), 0);
  std::vector<uint32_t> queue;
  auto visit = [&](int i, int j, int k) {
    const size_t id = g.index(i, j, k);
    if (!seen[id] && passable(g.state[id])) {
      seen[id] = 1;
      queue.push_back(static_cast<uint32_t>(id));
    }
  };
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        if (i == 0 || j == 0 || k == 0 || i == g.n[0] - 1 || j == g.n[1] - 1 || k == g.n[2] - 1) visit(i, j, k);
  for (size_t q = 0; q < queue.size(); ++q) {
    const uint32_t id = queue[q];
    const int i = static_cast<int>(id % g.n[0]), j = static_cast<int>((id / g.n[0]) % g.n[1]),
              k = static_cast<int>(id / (size_t(g.n[0]) * g.n[1]));
    if (i > 0) visit(i - 1, j, k);
    if (i + 1 < g.n[0]) visit(i + 1, j, k);
    if (j > 0) visit(i, j - 1, k);
    if (j + 1 < g.n[1]) visit(i, j + 1, k);
    if (k > 0) visit(i, j, k - 1);
    if (k + 1 < g.n[2]) visit(i, j, k + 1);
  }
  return seen;
}

// Steps 1-3: from the outermost cells through empty face neighbours; every
// empty cell reached becomes air.  Occupied cells stop the carving (Step
// 2.1); the occupied cells it touches are the paper's set T, and Steps 4-5
// grow S through occupied neighbours, which we do not need to store: the
// shell is every face between air and a non-air cell.
void carve_from_outside(CellGrid& g) {
  for (auto& s : g.state)
    if (s == CellGrid::kAir) s = CellGrid::kInside;
  const auto reached = flood_from_border(g, [](uint8_t s) { return s == CellGrid::kInside; });
  for (size_t id = 0; id < g.state.size(); ++id)
    if (reached[id]) g.state[id] = CellGrid::kAir;
}

// After filling: air that no longer reaches the outside is enclosed, so solid.
void enclose_pockets(CellGrid& g) {
  const auto reached = flood_from_border(g, [](uint8_t s) { return s == CellGrid::kAir; });
  for (size_t id = 0; id < g.state.size(); ++id)
    if (g.state[id] == CellGrid::kAir && !reached[id]) g.state[id] = CellGrid::kFilled;
}

// Carving through gaps of the sampling is stopped by a morphological
// closing: carve against the occupancy grown to 3x3x3 blocks (bridging gaps
// of up to two cells), then give back one layer: a grown-in cell without
// points that touches that carving's air (26 neighbours) is air again.
void carve_closed(CellGrid& g) {
  CellGrid grown = g;
  for (int k = 1; k + 1 < g.n[2]; ++k)
    for (int j = 1; j + 1 < g.n[1]; ++j)
      for (int i = 1; i + 1 < g.n[0]; ++i)
        if (g.state[g.index(i, j, k)] == CellGrid::kOccupied)
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) grown.state[grown.index(i + di, j + dj, k + dk)] = CellGrid::kOccupied;
  carve_from_outside(grown);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const size_t id = g.index(i, j, k);
        if (g.state[id] == CellGrid::kOccupied) continue;
        if (grown.state[id] == CellGrid::kAir) {
          g.state[id] = CellGrid::kAir;
          continue;
        }
        bool touches_air = false;
        for (int dk = -1; dk <= 1 && !touches_air; ++dk)
          for (int dj = -1; dj <= 1 && !touches_air; ++dj)
            for (int di = -1; di <= 1 && !touches_air; ++di) {
              const int x = i + di, y = j + dj, z = k + dk;
              if (x >= 0 && y >= 0 && z >= 0 && x < g.n[0] && y < g.n[1] && z < g.n[2])
                touches_air = grown.state[grown.index(x, y, z)] == CellGrid::kAir;
            }
        g.state[id] = touches_air ? CellGrid::kAir : CellGrid::kInside;
      }
  enclose_pockets(g);
}

// Fills air cells that make the solid's boundary non-manifold: in every
// 2x2 square of cells around a grid edge, two diagonal solid cells with two
// diagonal air cells; in every 2x2x2 block, two opposite-corner solid cells
// with six air cells, or two opposite-corner air cells with six solid ones.
// Returns how many cells were filled in this pass.
size_t fill_critical(CellGrid& g) {
  size_t filled = 0;
  auto air = [&](int i, int j, int k) { return g.state[g.index(i, j, k)] == CellGrid::kAir; };
  auto fill = [&](int i, int j, int k) {
    g.state[g.index(i, j, k)] = CellGrid::kFilled;
    ++filled;
  };
  for (int k = 0; k + 1 < g.n[2]; ++k)
    for (int j = 0; j + 1 < g.n[1]; ++j)
      for (int i = 0; i + 1 < g.n[0]; ++i) {
        // The three 2x2 squares through cell (i,j,k) in the xy, xz and yz planes.
        const int sq[3][4][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                                 {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},
                                 {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}};
        for (const auto& s : sq) {
          bool a[4];
          for (int c = 0; c < 4; ++c) a[c] = air(i + s[c][0], j + s[c][1], k + s[c][2]);
          if (a[0] == a[2] && a[1] == a[3] && a[0] != a[1]) {
            const int c = a[0] ? 0 : 1;
            fill(i + s[c][0], j + s[c][1], k + s[c][2]);
          }
        }
        // Opposite corners of the 2x2x2 block.
        bool b[8];
        int solids = 0;
        for (int c = 0; c < 8; ++c) solids += !(b[c] = air(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2)));
        if (solids == 2 || solids == 6) {
          for (int c = 0; c < 4; ++c) {
            if (b[c] == b[7 - c] && b[c] == (solids == 6)) {
              // Two lone corners of one kind: give the block a third cell of
              // the solid kind, which removes the corner-only contact.
              int f = solids == 6 ? c : (c ^ 1);
              fill(i + (f & 1), j + (f >> 1 & 1), k + (f >> 2));
              break;
            }
          }
        }
      }
  return filled;
}

}  // namespace

CellGrid carve(const PointCloud& pc, int grid, CarvingStats* stats) {
  grid = std::clamp(grid, 2, 1024);
  CellGrid g = make_grid(pc, grid);
  const size_t occupied = static_cast<size_t>(std::count(g.state.begin(), g.state.end(), CellGrid::kOccupied));
  carve_closed(g);
  size_t repaired = 0;
  for (int pass = 0; pass < 64; ++pass) {
    const size_t f = fill_critical(g);
    if (f == 0) break;
    repaired += f;
    enclose_pockets(g);  // a fill may enclose air, which is then solid
  }
  if (stats) {
    stats->grid = grid;
    stats->occupied = occupied;
    stats->solid = g.solid_count();
    stats->repaired = repaired;
  }
  return g;
}

int choose_grid(const PointCloud& pc, int max_grid) {
  // Closed means: no gap in the sampled shell is wider than the two cells
  // the closing in carve() bridges.  Gaps are measured by the spacing of the
  // points: the 95th percentile of each point's distance to its 6th nearest
  // neighbour.  A cell of 1.5 such spacings leaves every gap of that size
  // well inside one cell, so the finest closed grid is the longest side over
  // 1.5 spacings.
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < pc.size(); ++i)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double{pc.xyz[3 * i + a]}), hi[a] = std::max(hi[a], double{pc.xyz[3 * i + a]});
  const double longest = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const PointIndex index(pc);
  const double spacing = point_spacing(index, 6, 0.95);
  if (!(spacing > 0)) return 8;
  return std::clamp(static_cast<int>(longest / (1.5 * spacing)), 8, max_grid);
}

}  // namespace dbss
