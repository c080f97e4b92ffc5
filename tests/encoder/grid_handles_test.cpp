// The grid search (choose_carving) and a part whose handles all open at one
// grid: the libcgal-demo anchor (genus 4, four symmetric holes) sampled at
// 40,000 points.  At sampling seeds 2 and 3 the first grid (48 cells) has
// the holes filled and the next (52) shows all four at once (Euler
// characteristic 1 -> -3), which the search took for a leak and kept grid
// 48: a genus-0 control mesh over a genus-4 part.
#include <catch2/catch.hpp>

#include "../defect_shapes.h"
#include "../test_data.h"
#include "dbss/encoder/cell_carving.h"
#include "dbss/encoder/control_mesh.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/scan_check.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/point_index.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/surface_samples.h"

using namespace dbss;

TEST_CASE("grid search: four handles opening at one grid are the anchor's, not a leak") {
  const auto path = test::scan_data("data/meshes/anchor.off");
  if (!path) return;
  auto truth = read_mesh(*path);
  REQUIRE(truth.ok());
  REQUIRE(mesh_info(truth.value()).genus == 4);
  for (uint32_t seed : {1u, 2u, 3u}) {
    const std::vector<double> p = sample_surface(truth.value(), 40000, seed);
    PointCloud pc;
    pc.xyz.assign(p.begin(), p.end());
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
