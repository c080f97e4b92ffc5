// The grid search (choose_carving) and a part whose handles all open at one
// grid: the libcgal-demo anchor (genus 4, four symmetric holes) sampled at
// 40,000 points.  At sampling seeds 2 and 3 the first grid (48 cells) has
// the holes filled and the next (52) shows all four at once (Euler
// characteristic 1 -> -3), which the search took for a leak and kept grid
// 48: a genus-0 control mesh over a genus-4 part.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <mutex>

#include "../defect_shapes.h"
#include "../test_data.h"
#include "dbss/encoder/cell_carving.h"
#include "dbss/encoder/control_mesh.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/scan_check.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/point_index.h"
#include "dbss/io/geometry_files.h"

using namespace dbss;

TEST_CASE("grid search: four handles opening at one grid are the anchor's, not a leak") {
  const auto path = test::scan_data("data/meshes/anchor.off");
  if (!path) return;
  auto truth = read_mesh(*path);
  REQUIRE(truth.ok());
  REQUIRE(mesh_info(truth.value()).genus == 4);
  for (uint32_t seed : {1u, 2u, 3u}) {
    const PointCloud pc = test::sampled(truth.value(), 40000, seed);
    const PointIndex index(pc);
    const CarvingChoice chosen = choose_carving(pc, index);
    // A solid with g handles has Euler characteristic 1 - g.
    CAPTURE(seed, chosen.stats.grid);
    CHECK(carving_shape(chosen.cells).euler == -3);
    auto control = build_control_mesh(index, {});
    REQUIRE(control.ok());
    CHECK(mesh_info(control.value().control).genus == 4);
  }
}

// The clean triple torus at 4,000 points, seed 23: the middle torus's hole,
// narrowed by the side tori's tubes, shows only at the search's finest grid
// (36), whose carving needed 3 cells patched (the bound is 2) and so was
// taken for a leak: genus 2 with no warning.  The same grid moved by half a
// cell shows the third handle with no repair (cell_carving.cpp,
// handle_clean_moved).  Seed 7 is a neighbour that was right before.
TEST_CASE("grid search: a handle only the finest grid resolves, patched there, is kept from the moved carving") {
  const test::Shape& shape = test::genus_shape("triple torus");
  for (uint32_t seed : {23u, 7u}) {
    const PointCloud pc = test::sample_sdf(shape.sdf, shape.lo, shape.hi, 4000, seed);
    EncodeOptions o;
    o.levels = 1;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    CAPTURE(seed, e.value().stages.carving.grid, e.value().stages.carving.shift);
    CHECK(mesh_info(e.value().stages.control).genus == 3);
    CHECK(test::topology(TriangleMesh{e.value().levels.positions.back(), e.value().levels.triangles.back()}).genus == 3);
    for (const ScanWarning& w : e.value().check.warnings) CHECK(w.code != "topology");
  }
}

// The reviewer's worry about handles_resolved (several real holes through a
// thin wall opening at one grid): a plate 0.2 thick with 3 and 4 round holes
// through it, sampled, keeps every hole (scan_bench --plates).  Its holes
// open by one or two handles a grid, the search's ordinary rule; this pins
// that result should the rules for several handles at once change.
TEST_CASE("grid search: a plate with round holes through it keeps every hole") {
  for (int holes : {3, 4}) {
    const test::Shape plate = test::holed_plate(0.1, holes, 0.18);
    const PointCloud pc = test::sample_sdf(plate.sdf, plate.lo, plate.hi, 8000, 5);
    EncodeOptions o;
    o.levels = 1;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    CAPTURE(holes, e.value().stages.carving.grid);
    CHECK(mesh_info(e.value().stages.control).genus == holes);
  }
}

// The search on scripted carvings (search_carving_grids): each grid's Euler
// characteristic, enclosed volume and repairs as a table, so a sequence of
// grids the real data meets rarely can be pinned.  Every carving holds 1,000
// occupied cells (a patch bound of 2 repairs) and the same volume unless
// the table says otherwise.
namespace {
struct Look {
  int64_t euler;
  size_t repaired = 0;
  double volume = 1;
};
// `finest`, when given: the finest grid looked at (the search may look from
// two threads at once).
CarvingChoice scripted_search(const std::vector<int>& grids, const std::map<std::pair<int, int>, Look>& table,
                              int max_grid = 1024, int* finest = nullptr) {
  std::mutex looked;
  return search_carving_grids(grids, [&](int grid, double shift) {
    if (finest) {
      const std::lock_guard<std::mutex> lock(looked);
      *finest = std::max(*finest, grid);
    }
    const auto it = table.find({grid, shift > 0});
    // A grid not in the table looks like grid 0's entry at that shift.
    const Look l = it != table.end() ? it->second : table.at({0, shift > 0});
    CarvingTrial t;
    t.carving.stats.grid = grid;
    t.carving.stats.shift = shift;
    t.carving.stats.occupied = 1000;
    t.carving.stats.repaired = l.repaired;
    t.shape.euler = l.euler;
    t.shape.inside_volume = l.volume;
    return t;
  }, max_grid);
}
}  // namespace

// The reviewer's first point: a patched grid whose moved carving shows a
// handle with no repair was kept without asking the finer grids.  Here grid
// 11 (patched, Euler -1) moved by half a cell shows the handle cleanly, but
// grids 12 and 13 (patched too, so leaks) show no handle at either
// placement: the handle is the placement's luck.  The old search shipped
// grid 11 moved, a false handle with no leak noted; now grid 10 is kept
// and 11 is reported as the leak.
TEST_CASE("grid search: a moved carving's handle must persist at the next grids") {
  const std::map<std::pair<int, int>, Look> table{
      {{0, 0}, {0}},     {{0, 1}, {0}},     {{10, 0}, {0}},     {{11, 0}, {-1, 5}}, {{11, 1}, {-1}},
      {{12, 0}, {0, 5}}, {{12, 1}, {0, 5}}, {{13, 0}, {0, 5}}, {{13, 1}, {0, 5}}};
  const CarvingChoice c = scripted_search({10, 11, 12, 13}, table);
  CHECK(c.stats.grid == 10);
  CHECK(c.stats.shift == 0);
  CHECK(c.leaking_grid == 11);
  // The same handle at the finest grid: the grids past it (12, 13, carved
  // for the test only) must show it.  They do not here...
  const CarvingChoice last = scripted_search({10, 11}, table);
  CHECK(last.stats.grid == 10);
  CHECK(last.leaking_grid == 11);
  // ... and where they do (at either placement), the moved carving is kept.
  std::map<std::pair<int, int>, Look> persists = table;
  persists[{12, 1}] = {-1};
  persists[{13, 0}] = {-2, 5};
  const CarvingChoice kept = scripted_search({10, 11}, persists);
  CHECK(kept.stats.grid == 11);
  CHECK(kept.stats.shift == 0.5);
  CHECK(kept.leaking_grid == 0);
}

// The reviewer's second point: a grid that adds a handle (11: Euler 0 -> -1)
// is carved moved, and the moved carving (Euler 0) kept; its shape was not,
// so grid 12's Euler -3 was compared with -1 (a drop of two: no tear) and
// not with the kept carving's 0 (three: a tear).  Grids 13 and 14 go on
// tearing, so the search ends on grid 11 moved; the old search went on to
// 14.
TEST_CASE("grid search: a later tear is measured from the moved carving kept") {
  const std::map<std::pair<int, int>, Look> table{{{0, 0}, {0}},   {{0, 1}, {0}},   {{10, 0}, {0}},  {{11, 0}, {-1}},
                                                  {{11, 1}, {0}},  {{12, 0}, {-3}}, {{12, 1}, {-3}}, {{13, 0}, {-4}},
                                                  {{13, 1}, {-4}}, {{14, 0}, {-5}}, {{14, 1}, {-5}}};
  const CarvingChoice c = scripted_search({10, 11, 12, 13, 14}, table);
  CHECK(c.stats.grid == 11);
  CHECK(c.stats.shift == 0.5);
  CHECK(c.leaking_grid == 12);
}

// The grids past the last, carved only to see a handle persist, stop at the
// search's cap (choose_carving's max_grid, which bounds the carving's
// memory); the search capped at 256 cells went on to 277 and 300.  Grid 11
// moved shows a handle that grids 12 and 13 show too: kept when the cap
// allows 13, not seen to persist when it stops at 12 (grid 10 stands, 11
// is the leak; at a cap of 11 likewise), and nothing past the cap is
// carved either way.
TEST_CASE("grid search: no grid past the cap is carved to see a handle persist") {
  const std::map<std::pair<int, int>, Look> table{
      {{0, 0}, {0}},      {{0, 1}, {0}},      {{10, 0}, {0}},     {{11, 0}, {-1, 5}}, {{11, 1}, {-1}},
      {{12, 0}, {0, 5}},  {{12, 1}, {-1}},    {{13, 0}, {-2, 5}}, {{13, 1}, {0, 5}}};
  // The cap, then the finest grid looked at and the choice.
  struct Case {
    int cap, finest, grid;
    double shift;
    int leaking;
  };
  for (const Case& c : {Case{12, 12, 10, 0, 11}, Case{13, 13, 11, 0.5, 0}, Case{11, 11, 10, 0, 11}}) {
    INFO("cap " << c.cap);
    int finest = 0;
    const CarvingChoice got = scripted_search({10, 11}, table, c.cap, &finest);
    CHECK(finest == c.finest);
    CHECK(got.stats.grid == c.grid);
    CHECK(got.stats.shift == c.shift);
    CHECK(got.leaking_grid == c.leaking);
  }
}
