// Issue 15's level targets on shapes built here, against their exact
// surfaces: no level farther from the true surface than the one before
// (within 2%), and levels past the points' density cheap.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "../sampled_shapes.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/triangle_tree.h"
#include "dbss/measure/surface_samples.h"

using namespace dbss;

namespace {

// Two-sided mean distance between a level and the zero set of `sdf`: from
// area-uniform samples of the level, |sdf| (exact for the tori's distance
// functions); from fresh points of the true surface, the exact distance to
// the level's triangles.
double two_sided(const TriangleMesh& level, const test::Shape& s, const std::vector<double>& truth_points) {
  const std::vector<double> on_level = sample_surface(level, truth_points.size() / 3, 5);
  double to_truth = 0, to_level = 0;
  for (size_t i = 0; i < on_level.size(); i += 3) to_truth += std::abs(s.sdf(on_level[i], on_level[i + 1], on_level[i + 2]));
  const TriangleTree tree(level);
  for (size_t i = 0; i < truth_points.size(); i += 3) to_level += tree.distance(&truth_points[i]);
  return 0.5 * (to_truth / static_cast<double>(on_level.size() / 3) + to_level / static_cast<double>(truth_points.size() / 3));
}

}  // namespace

TEST_CASE("levels against the true surface: no level farther than the one before, and levels past the points cheap") {
  // 3,000 points: the control mesh's level 2 or 3 already has more vertices
  // than points, so levels 3-5 are past the points' density.  Before issue
  // 15's fixes the fit's own error was coded as detail there and the error
  // rose from level to level.
  const std::vector<test::Shape> shapes = test::genus_shapes();
  for (const test::Shape& s : shapes) {
    const std::string name = s.name;
    if (name != "torus" && name != "double torus") continue;
    INFO(name);
    const PointCloud pc = test::sample_sdf(s.sdf, s.lo, s.hi, 3000);
    const PointCloud truth = test::sample_sdf(s.sdf, s.lo, s.hi, 20000, 99);
    const std::vector<double> truth_points(truth.xyz.begin(), truth.xyz.end());
    EncodeOptions o;
    o.levels = 5;
    auto e = encode_points(pc, o);
    REQUIRE(e.ok());
    const Encoding& enc = e.value();
    double previous = 0;
    for (uint32_t l = 0; l <= 5; ++l) {
      const TriangleMesh level{enc.levels.positions[l], enc.levels.triangles[l]};
      const double error = two_sided(level, s, truth_points) / enc.diagonal;
      INFO("level " << l << ": " << level.vertex_count() << " vertices, error " << error << " of the diagonal, previous "
                    << previous << ", prefix " << prefix_bytes(enc, l) << " bytes");
      if (l > 0) CHECK(error <= 1.02 * previous);
      // Once the level before has more vertices than points, this one costs
      // at most half as much again.
      if (l > 0 && enc.levels.positions[l - 1].size() / 3 > pc.size())
        CHECK(prefix_bytes(enc, l) <= 1.5 * static_cast<double>(prefix_bytes(enc, l - 1)));
      previous = error;
    }
  }
}
