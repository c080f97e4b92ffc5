// The wedge sampler's gate (dbss/encoder/crease_lines.h): the tagged edges
// reach a neighbourhood beyond themselves and no further, so a smooth region
// curved tightly enough to pass for two planes is sampled as without the
// wedge.
#include <catch2/catch.hpp>

#include <cmath>

#include "../crease_shapes.h"
#include "../sampled_shapes.h"
#include "../shapes.h"
#include "dbss/encoder/crease_align.h"
#include "dbss/encoder/crease_lines.h"
#include "dbss/encoder/sampling.h"

using namespace dbss;

namespace {

TriangleMesh moved(TriangleMesh m, float dx) {
  for (size_t i = 0; i < m.positions.size(); i += 3) m.positions[i] += dx;
  return m;
}

}  // namespace

TEST_CASE("crease lines: near a tagged edge within its reach and not elsewhere") {
  const TriangleMesh cube = test::cube();
  const format::Creases tags = test::creases_from_dihedral(cube, 30);
  const PointCloud pc = test::sampled(cube, 20000, 5);
  const PointIndex index(pc);
  const CreaseLines lines(cube, tags, index, 0.5, 32);
  CHECK(lines.size() == 12);  // the cube's edges, not its faces' diagonals
  const double beside[3] = {0.99, 0.98, 0.3}, corner[3] = {1.02, -1.01, 0.99}, far[3] = {0, 0, 3}, face[3] = {0, 0, 1},
               centre[3] = {0, 0, 0};
  CHECK(lines.near(beside));
  CHECK(lines.near(corner));
  CHECK_FALSE(lines.near(far));
  // A face's centre is 1 from four edges: within half an edge (2) plus a
  // neighbourhood; the cube's centre is 1.41 from the nearest.
  CHECK(lines.near(face));
  CHECK_FALSE(lines.near(centre));
  // No tags, no lines.
  const CreaseLines none(cube, format::Creases{}, index, 0.5, 32);
  CHECK(none.empty());
  CHECK_FALSE(none.near(beside));
}

TEST_CASE("a thin tube with the crease lines elsewhere: no wedge samples and the same distances as without the wedge") {
  // Tube radius 0.05 at 18k points: its 32 nearest points span about 1.5
  // radii, so two fitted planes can meet at over 30 degrees there.
  // The cube's points are in the cloud too: a part with creases and,
  // elsewhere, a tightly curved smooth region.
  const TriangleMesh tube = test::torus(160, 24, 1.0f, 0.05f);
  const TriangleMesh cube = moved(test::cube(), 10);
  PointCloud pc = test::sampled(tube, 18000, 5);
  const PointCloud cube_points = test::sampled(cube, 20000, 5);
  pc.xyz.insert(pc.xyz.end(), cube_points.xyz.begin(), cube_points.xyz.end());
  const PointIndex index(pc);
  const std::vector<float> normals = estimate_point_normals(index, 2);
  const CreaseLines lines(cube, test::creases_from_dihedral(cube, 30), index, 0.5, 32);
  REQUIRE(lines.size() == 12);
  const double min_cos = std::cos(30 * 3.14159265358979323846 / 180);
  size_t ungated = 0, gated = 0, differ = 0, probes = 0;
  for (int i = 0; i < 400; ++i) {
    // Probes on the tube, a little off it along its normal.
    const double u = 2 * 3.14159265358979323846 * (i + 0.5) / 400, v = 2.399963 * i;
    const double n[3] = {std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v)};
    const double r = 0.05 + 0.002 * ((i % 5) - 2);
    const double p[3] = {std::cos(u) + r * n[0], std::sin(u) + r * n[1], r * n[2]};
    PointSides off{&normals, min_cos, false}, anywhere{&normals, min_cos, true}, gate{&normals, min_cos, true};
    gate.lines = &lines;
    SampleScratch scratch;
    const Sample a = sample_displacement(index, p, n, 0.02, 0.02, scratch, true, &off);
    const Sample b = sample_displacement(index, p, n, 0.02, 0.02, scratch, true, &anywhere);
    const Sample c = sample_displacement(index, p, n, 0.02, 0.02, scratch, true, &gate);
    ungated += b.wedge, gated += c.wedge, differ += a.distance != c.distance;
    ++probes;
  }
  CAPTURE(probes, ungated, gated, differ);
  // The test has teeth: ungated, the wedge fires on this smooth tube.
  CHECK(ungated > 0);
  CHECK(gated == 0);
  CHECK(differ == 0);
}
