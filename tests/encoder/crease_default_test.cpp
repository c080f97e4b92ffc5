// Creases on by default (issue 16): the options `dbss encode`, `dbss
// compare` and the Python binding start from (tools::set_command_defaults)
// find creases.  A smooth shape gets no tag, so its file is the one
// --no-creases writes, byte for byte; a cube gets its edges tagged and its
// level 3 stays within 1% of the diagonal of the truth everywhere.  Sampled
// as crease_bench samples (area-uniform, fixed seeds).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "../crease_shapes.h"
#include "../sampled_shapes.h"
#include "../shapes.h"
#include "../test_data.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/io/geometry_files.h"
#include "dbss/measure/mesh_distance.h"
#include "encode_options.h"

using namespace dbss;

namespace {

// The command's options after `args`, as `dbss encode` parses them, with a
// fixed level count (auto is not what these tests are about, and costs).
EncodeOptions command_options(const std::vector<std::string_view>& args, uint32_t levels) {
  EncodeOptions o;
  tools::set_command_defaults(o);
  for (size_t i = 0; i < args.size(); ++i) {
    std::string error;
    REQUIRE(tools::parse_encode_option(args, i, o, error) == tools::OptionParse::ok);
  }
  o.levels = levels;
  o.threads = 2;
  return o;
}

double diagonal(const TriangleMesh& m) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < m.positions.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], double{m.positions[i]}), hi[i % 3] = std::max(hi[i % 3], double{m.positions[i]});
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

}  // namespace

TEST_CASE("the commands' defaults have creases on and --no-creases or --crease-angle off turn them off") {
  CHECK(command_options({}, 1).creases.angle_degrees == tools::kCommandCreaseAngle);
  CHECK(tools::kCommandCreaseAngle > 0);
  CHECK(command_options({"--no-creases"}, 1).creases.angle_degrees == 0);
  CHECK(command_options({"--crease-angle", "off"}, 1).creases.angle_degrees == 0);
  CHECK(command_options({"--crease-angle", "45"}, 1).creases.angle_degrees == 45);
}

TEST_CASE("a sampled torus and sphere under the default options: no tag and the file --no-creases writes") {
  struct Case {
    const char* name;
    TriangleMesh mesh;
  };
  const Case cases[] = {{"torus", test::torus(96, 48)}, {"sphere", test::uv_sphere(48, 64)}};
  for (const Case& c : cases)
    for (uint32_t seed : {1u, 2u}) {
      INFO(c.name << " seed " << seed);
      const PointCloud pc = test::sampled(c.mesh, 30000, seed);
      auto on = encode_points(pc, command_options({}, 2));
      auto off = encode_points(pc, command_options({"--no-creases"}, 2));
      REQUIRE(on.ok());
      REQUIRE(off.ok());
      CHECK(on.value().creases.edges_tested > 0);  // the detector ran and found nothing
      CHECK(on.value().contents.creases.empty());
      CHECK(on.value().bytes == off.value().bytes);
    }
}

TEST_CASE("a sampled cube under the default options gets crease tags and level 3 within 1% of the diagonal") {
  const TriangleMesh cube = test::cube();
  const double diag = diagonal(cube);
  const PointCloud pc = test::sampled(cube, 40000, 1);
  auto e = encode_points(pc, command_options({}, 3));
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  CHECK(enc.creases.creases >= 12);
  CHECK(!enc.contents.creases.empty());
  CHECK(enc.contents.header.version_minor >= format::kCreaseVersionMinor);
  const TriangleMesh l3{enc.levels.positions[3], enc.levels.triangles[3]};
  const MeshDistance d = mesh_distance(l3, cube, {200000, 1, 2});
  // 0.39% with creases on (crease_bench, seed 1); several percent off.
  CHECK(d.max() / diag < 0.01);
}

TEST_CASE("the libcgal-demo fandisk (seed 2) under the default options: level 3 within 1% of the diagonal at its thin flange") {
  // The flange's two faces are 0.04 apart with parallel normals; where the
  // points nearest a level-1 odd vertex's line were mostly the far face's,
  // the one-sided sampler took both faces for one sheet and hit between
  // them: the vertex 0.018 inside, 1.31% of the diagonal at level 3
  // (sampling.cpp, kSteepOneSided; 0.90% with it, crease_bench).
  const auto path = test::scan_data("data/meshes/fandisk.off");
  if (!path) return;
  auto read = read_mesh(*path);
  REQUIRE(read.ok());
  const TriangleMesh truth = std::move(read).value();
  const double diag = diagonal(truth);
  auto e = encode_points(test::sampled(truth, 40000, 2), command_options({}, 3));
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  REQUIRE(!enc.contents.creases.empty());
  const TriangleMesh l3{enc.levels.positions[3], enc.levels.triangles[3]};
  const MeshDistance d = mesh_distance(l3, truth, {200000, 1, 2});
  CAPTURE(d.max() / diag, d.mean() / diag);
  CHECK(d.max() / diag < 0.01);
}

TEST_CASE("the libcgal-demo anchor (seed 1) under the default options: level 3 within 1% of the diagonal and no level worse than the last") {
  // Its level-3 Hausdorff point was a level-1 odd vertex beside a line:
  // a sliver's corner on a tagged edge, and short untagged edges whose
  // rings reach 10-45 of their lengths (1.42% of the diagonal; 0.78% with
  // the slivers flipped and the short edges collapsed: creases.cpp,
  // crease_slivers.h, crease_short_edges.h; bench/crease_bench.md,
  // fifteenth session).
  const auto path = test::scan_data("data/meshes/anchor.off");
  if (!path) return;
  auto read = read_mesh(*path);
  REQUIRE(read.ok());
  const TriangleMesh truth = std::move(read).value();
  const double diag = diagonal(truth);
  auto e = encode_points(test::sampled(truth, 40000, 1), command_options({}, 3));
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  REQUIRE(!enc.contents.creases.empty());
  // The reported count is the file's: a sliver flip splits one tag in two.
  const auto tagged = std::count_if(enc.contents.creases.edge.begin(), enc.contents.creases.edge.end(), [](uint8_t b) { return b != 0; });
  CAPTURE(enc.creases.sliver_flips, enc.creases.short_collapses);
  CHECK(enc.creases.creases == static_cast<size_t>(tagged));
  double last = INFINITY;
  for (uint32_t l = 0; l <= 3; ++l) {
    const TriangleMesh level{enc.levels.positions[l], enc.levels.triangles[l]};
    const MeshDistance d = mesh_distance(level, truth, {200000, 1, 2});
    CAPTURE(l, d.max() / diag, d.mean() / diag, last);
    CHECK(d.mean() / diag <= last);
    last = d.mean() / diag;
    if (l == 3) CHECK(d.max() / diag < 0.01);
  }
}

TEST_CASE("a capped cylinder (seed 2) under the defaults: off-point vertices settled onto the wall and level 3 within 1%") {
  // The control-mesh builder left an untagged vertex of valence 3 0.036
  // outside the wall, past one edge of its own ring, where the projection
  // could not move it without turning a triangle over; the butterfly keeps
  // it at every level (level 3 Hausdorff 1.03% of the diagonal; 0.48% with
  // it settled onto the points: crease_off_points.h, bench/crease_bench.md,
  // sixteenth session).  The pass is on by default; the control vertex
  // check below fails with it off.
  const TriangleMesh truth = test::capped_cylinder(64, 9);
  const double diag = diagonal(truth);
  EncodeOptions o = command_options({}, 3);
  auto e = encode_points(test::sampled(truth, 40000, 2), o);
  REQUIRE(e.ok());
  const Encoding& enc = e.value();
  REQUIRE(!enc.contents.creases.empty());
  CHECK(enc.creases.settled > 0);
  const TriangleTree tree(truth);
  double worst = 0;
  for (size_t v = 0; v < enc.control.vertex_count(); ++v) {
    const double p[3] = {enc.control.positions[3 * v], enc.control.positions[3 * v + 1], enc.control.positions[3 * v + 2]};
    double c[3];
    tree.closest_point(p, c);
    worst = std::max(worst, std::sqrt((p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) + (p[2] - c[2]) * (p[2] - c[2])));
  }
  // No control vertex alone takes a level past the 1% bound: 1.05% of the
  // diagonal without the pass, 0.70% with it (another vertex).
  CAPTURE(worst / diag);
  CHECK(worst / diag < 0.01);
  const TriangleMesh l3{enc.levels.positions[3], enc.levels.triangles[3]};
  const MeshDistance d = mesh_distance(l3, truth, {200000, 1, 2});
  CAPTURE(d.max() / diag, d.mean() / diag);
  CHECK(d.max() / diag < 0.01);
}
