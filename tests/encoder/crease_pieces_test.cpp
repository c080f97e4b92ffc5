// Fourteenth session's crease changes (issue 16).  Tags in pieces
// (CreaseOptions::max_dart_share): on libcgal-demo's couplingdown, a
// coarse faceted part whose chamfers and thin rims are under the control
// mesh's resolution, the detector tagged stretches of them with a dart at
// nearly every other end, and creases on came out worse than off (level 3
// +12% error at 40,000 points, +20% at 30,000); such a tag set is dropped,
// so creases on is never worse there.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "../sampled_shapes.h"
#include "../test_data.h"
#include "dbss/encoder/encode.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"
#include "dbss/measure/surface_samples.h"

using namespace dbss;

TEST_CASE("couplingdown's tags in pieces are dropped and creases on is no worse than off") {
  const auto path = test::scan_data("data/meshes/couplingdown.off");
  if (!path) return;
  auto read = read_mesh(*path);
  REQUIRE(read.ok());
  const TriangleMesh truth = std::move(read).value();
  const PointCloud pc = test::sampled(truth, 30000, 1);
  auto on = encode_points(pc, test::crease_options(30, 3));
  auto off = encode_points(pc, test::crease_options(0, 3));
  REQUIRE(on.ok());
  REQUIRE(off.ok());
  // The detector ran and found crease edges, most ending in darts.
  CHECK(on.value().creases.in_pieces_dropped > 0);
  const TriangleMesh l_on{on.value().levels.positions[3], on.value().levels.triangles[3]};
  const TriangleMesh l_off{off.value().levels.positions[3], off.value().levels.triangles[3]};
  const double e_on = mesh_distance(l_on, truth, {100000, 1, 2}).mean();
  const double e_off = mesh_distance(l_off, truth, {100000, 1, 2}).mean();
  INFO("level 3 error on " << e_on << " off " << e_off << ", bytes on " << on.value().bytes.size() << " off "
                           << off.value().bytes.size());
  // Before the test: on 1.012e-3 of the diagonal against off 8.4e-4 (+20%).
  CHECK(e_on <= 1.001 * e_off);
  CHECK(on.value().bytes.size() <= off.value().bytes.size());
}
