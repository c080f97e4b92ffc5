// The encoder on real scans: the libcgal-demo point sets (files nobody here
// made: one-sided scans, lidar, a noisy blob) and the bunny with defects
// made from it.  Each result is either sane (clamped displacements and
// distance to the points within bounds) or warned about; where the right
// answer is known (an open half sphere, a closed bunny) it is asserted.
#include <catch2/catch.hpp>

#include <string>

#include "../defect_shapes.h"
#include "../test_data.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/shell_mesh.h"

using namespace dbss;
namespace dt = dbss::test;

namespace {

struct Run {
  Encoding e;
  MeshInfo info;     // of the finest level
  double clamped = 0;
  double distance = 0;  // points -> finest surface, mean, in median spacings
};

Run encode(const PointCloud& pc, uint32_t levels) {
  EncodeOptions o;
  o.levels = levels;
  auto e = encode_points(pc, o);
  REQUIRE(e.ok());
  Run r;
  r.e = std::move(e).value();
  const TriangleMesh finest{r.e.levels.positions.back(), r.e.levels.triangles.back()};
  r.info = mesh_info(finest);
  const LevelStats& s = r.e.levels.stats.back();
  r.clamped = double(s.clamped) / double(std::max<size_t>(1, s.odd));
  r.distance = points_to_mesh(r.e.points.xyz, finest).mean / r.e.check.spacing;
  return r;
}

double error_on(const PointCloud& points, const Encoding& e) {
  return points_to_mesh(points.xyz, {e.levels.positions.back(), e.levels.triangles.back()}).mean;
}

}  // namespace

TEST_CASE("libcgal-demo scans: every result is within the bounds or warned about") {
  struct Scan {
    const char* file;
    uint32_t levels;
  };
  // building.ply (100,000 lidar points) at one level: it is the slow one.
  for (const Scan& s : {Scan{"hippo1.ply", 2}, Scan{"half.xyz", 2}, Scan{"building.ply", 1}, Scan{"oni.ply", 2},
                        Scan{"fin90_with_PCA_normals.xyz", 2}, Scan{"blobby.xyz", 2}}) {
    INFO(s.file);
    const auto path = dt::scan_data(std::string("data/points_3/") + s.file);
    if (!path) continue;
    auto pc = read_points(*path);
    REQUIRE(pc.ok());
    const Run r = encode(pc.value(), s.levels);
    INFO("clamped " << r.clamped << ", distance " << r.distance << " spacings, " << r.e.check.warnings.size()
                    << " warning(s), surface " << r.e.stages.surface_reason);
    CHECK(r.info.manifold);
    // The self-check reports what the test measures.
    CHECK(r.e.check.clamped_share == Approx(r.clamped));
    CHECK(r.e.check.surface_components == r.info.components);
    const bool sane = r.clamped <= 0.02 && r.distance <= 3;
    CHECK((sane || !r.e.check.warnings.empty()));
  }
}

TEST_CASE("libcgal-demo scans: one-sided scans come out open, the half sphere with one boundary loop") {
  for (const char* file : {"half.xyz", "hippo1.ply", "fin90_with_PCA_normals.xyz"}) {
    INFO(file);
    const auto path = dt::scan_data(std::string("data/points_3/") + file);
    if (!path) continue;
    auto pc = read_points(*path);
    REQUIRE(pc.ok());
    const Run r = encode(pc.value(), 1);
    CHECK(r.e.stages.open);
    CHECK_FALSE(r.info.closed);
    CHECK(r.e.check.warnings.empty());
    if (std::string(file) == "half.xyz") {
      CHECK(r.info.components == 1);
      CHECK(r.info.boundary_loops == 1);
      CHECK(r.info.genus == 0);
    }
  }
}

TEST_CASE("bunny with stray points or its base unscanned: one closed genus-0 surface near the clean result") {
  const auto path = dt::scan_data("data/meshes/bunny00.off");
  if (!path) return;
  auto read = read_points(*path);
  REQUIRE(read.ok());
  const PointCloud& clean = read.value();
  const Run base = encode(clean, 2);
  REQUIRE(base.info.closed);
  const double clean_error = error_on(clean, base.e);
  {
    INFO("0.5% outliers in the bounding box");
    const Run r = encode(dt::with_outliers(clean, 0.005, 3), 2);
    CHECK(r.info.closed);
    CHECK(r.info.components == 1);
    CHECK(r.info.genus == 0);
    // Measured on the clean points: 1.01x the clean result's.
    CHECK(error_on(clean, r.e) <= 1.2 * clean_error);
    CHECK(r.e.check.warnings.empty());
  }
  {
    // A scan of an object on a table: the base (the lowest 12% of the
    // surface along the bunny's up axis, -y) never scanned.
    INFO("base unscanned");
    const PointCloud cut = dt::with_slab_cut(clean, {0, -1, 0}, 0.12);
    const Run r = encode(cut, 2);
    CHECK_FALSE(r.e.stages.open);
    CHECK(r.e.stages.bridged_area > 0);
    CHECK(r.info.closed);
    CHECK(r.info.components == 1);
    CHECK(r.info.genus == 0);
    // On the scanned part, against the complete scan's result there.
    CHECK(error_on(cut, r.e) <= 1.3 * error_on(cut, base.e));
    CHECK(r.e.check.warnings.empty());
  }
}
