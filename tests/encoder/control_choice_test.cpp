// The point path's control choice (encoder/src/control_choice.h): on a
// noisy cloud the crossing level's distance to the points does not veto the
// quarter mesh; on a clean cloud every level is a target, as before.  Draco's
// bits on a clean cloud: the fewest whose curve dominates level 0's.
#include <catch2/catch.hpp>

#include <vector>

#include "../../encoder/src/control_choice.h"
#include "dbss/io/geometry_files.h"

namespace dbss {

namespace {

// rd_bench's noisy knot1 (30,000 points, noise 2e-3 of the diagonal, seed
// 1): each candidate's curve as the encoder measured it (bytes, distance to
// the points in model units, vertices).  The default's crossing level
// (79,424 vertices) is 2% nearer the points than the quarter's, which is
// why the plain rule kept the default; against the true surface the
// quarter's file is 7% nearer at its finest level in 40% fewer bytes
// (bench/rd_bench.md, fifteenth session).
const std::vector<RdPoint> kKnotQuarter = {
    {1400, 0.0037, 310}, {2000, 0.00201, 1240}, {3700, 0.0016, 4960}, {7400, 0.0015, 19840}, {14600, 0.00146, 79360}};
const std::vector<RdPoint> kKnotDefault = {{4600, 0.0025, 1241}, {6500, 0.00171, 4964}, {11900, 0.00149, 19856}, {21800, 0.00143, 79424}};
constexpr size_t kPoints = 30000;

// The noisy armadillo's (same settings): the quarter never comes within 2%
// of the default's level 2 (0.252), so its detail keeps the default.
// (Only the fine curve's vertex counts are read.)
const std::vector<RdPoint> kArmadilloQuarter = {
    {1300, 0.625, 271}, {1900, 0.415, 1084}, {3700, 0.318, 4336}, {8000, 0.28, 17344}, {16400, 0.264, 69376}};
const std::vector<RdPoint> kArmadilloDefault = {{4100, 0.415, 1087}, {6000, 0.294, 4342}, {11300, 0.252, 17362}, {22000, 0.238, 69442}};

}  // namespace

TEST_CASE("control choice: on a noisy cloud the crossing level does not veto the quarter") {
  // The plain rule (every level a target) refuses it: the quarter's floor
  // misses 1.02 x 0.00143.  This is the old behaviour on every cloud.
  CHECK_FALSE(rd_curve_dominates(kKnotQuarter, kKnotDefault));
  CHECK(keep_coarse_control(kKnotQuarter, kKnotDefault, true, kPoints));
  // A clean cloud's floor is the shape's: it stays a target.
  CHECK_FALSE(keep_coarse_control(kKnotQuarter, kKnotDefault, false, kPoints));
}

TEST_CASE("control choice: on a noisy cloud the levels before the crossing are still targets") {
  CHECK_FALSE(keep_coarse_control(kArmadilloQuarter, kArmadilloDefault, true, kPoints));
  // A quarter that is cheaper at the floor but misses an earlier level.
  std::vector<RdPoint> worse = kKnotQuarter;
  worse[3].error = 0.0016;  // never within 2% of the default's 0.00149 before its floor
  worse[4].error = 0.0016;
  CHECK_FALSE(keep_coarse_control(worse, kKnotDefault, true, kPoints));
  // A file that stops before the points' density has no crossing level:
  // every level is a target (the plain rule), noisy or not.
  const std::vector<RdPoint> short_fine(kKnotDefault.begin(), kKnotDefault.end() - 1);
  const std::vector<RdPoint> short_coarse = {{1400, 0.0037, 310}, {2000, 0.00201, 1240}, {3700, 0.00155, 4960}};
  CHECK(keep_coarse_control(short_coarse, short_fine, true, kPoints) == rd_curve_dominates(short_coarse, short_fine));
  CHECK_FALSE(keep_coarse_control(short_coarse, short_fine, true, kPoints));
}

namespace {

// rd_bench's clean armadillo (30,000 points, seed 1, --levels 6): the
// default mesh (2,752 faces) at level 0's 10 bits and at 9 and 8, up to
// the crossing level, as choose_control_bits measured them (bytes, the
// area-weighted distance to the points in model units).  At 9 bits every
// level is within 1% for 0.3-0.6 KB less; at 8 bits level 2 is 4% farther
// (bench/rd_bench.md, sixteenth session).
const std::vector<RdPoint> kArmadillo10 = {{3900, 0.187}, {6600, 0.12}, {14700, 0.0808}, {30900, 0.0692}};
const std::vector<RdPoint> kArmadillo9 = {{3300, 0.192}, {6000, 0.121}, {14200, 0.0816}, {30600, 0.0696}};
const std::vector<RdPoint> kArmadillo8 = {{2700, 0.212}, {5500, 0.128}, {13900, 0.0841}, {31400, 0.0703}};

// The clean elephant's (same settings, 2,956 faces): fewer bits are cheaper
// at level 0 but leave the floor 6% farther from the points (against the
// truth the last session measured 9 bits 14% farther at the finest level).
const std::vector<RdPoint> kElephant11 = {{4600, 0.000605}, {7000, 0.000429}, {13800, 0.000288}, {22800, 0.000265}};
const std::vector<RdPoint> kElephant10 = {{4000, 0.000613}, {6500, 0.000471}, {13300, 0.000302}, {22600, 0.000282}};
const std::vector<RdPoint> kElephant9 = {{3400, 0.00065}, {5900, 0.000455}, {12900, 0.000305}, {22800, 0.000281}};

}  // namespace

TEST_CASE("control bits: the area-weighted distance counts each vertex by the surface it stands for") {
  // Points on the plane z = 0 over the unit square; the level is that
  // square (2 triangles, on the points) plus a patch of 10 x 10 vertices
  // 0.01 wide lifted 0.05 off the plane.  Over the vertices the patch's 100
  // vertices carry the vertices' half (about 0.048, so the mean of the two
  // halves is about 0.024); over the area they stand for 1e-4 of it.
  // Without the weighting both figures are 0.024.
  PointCloud pc;
  for (int i = 0; i <= 100; ++i)
    for (int j = 0; j <= 100; ++j) pc.xyz.insert(pc.xyz.end(), {0.01f * static_cast<float>(i), 0.01f * static_cast<float>(j), 0.0f});
  const PointIndex index(pc);
  std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  std::vector<uint32_t> triangles = {0, 1, 2, 0, 2, 3};
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      positions.insert(positions.end(), {0.5f + 0.001f * static_cast<float>(i), 0.5f + 0.001f * static_cast<float>(j), 0.05f});
  for (uint32_t i = 0; i < 9; ++i)
    for (uint32_t j = 0; j < 9; ++j) {
      const uint32_t a = 4 + 10 * i + j;
      triangles.insert(triangles.end(), {a, a + 10, a + 11, a, a + 11, a + 1});
    }
  const double by_vertex = level_distance_to_points(positions, triangles, index);
  const double by_area = level_distance_to_points(positions, triangles, index, true);
  INFO("over the vertices " << by_vertex << ", over the area " << by_area);
  // The points' half is the same in both (the points are all on the square).
  CHECK(by_vertex > 0.02);
  CHECK(by_area < 0.001);
}

TEST_CASE("control bits: fewer bits are kept where their curve reaches every level in no more bytes") {
  // Level 0's bits (the old rule, 10) are not the armadillo's best: 9 reaches
  // every level of 10's curve in fewer bytes; 8 misses level 2.
  CHECK(fewest_control_bits(10, kArmadillo10, {{9, kArmadillo9}, {8, kArmadillo8}}) == 9);
  CHECK(rd_curve_dominates(kArmadillo9, kArmadillo10));
  CHECK_FALSE(rd_curve_dominates(kArmadillo8, kArmadillo10));
  // The order of the candidates does not matter.
  CHECK(fewest_control_bits(10, kArmadillo10, {{8, kArmadillo8}, {9, kArmadillo9}}) == 9);
}

TEST_CASE("control bits: the elephant keeps level 0's bits") {
  CHECK(fewest_control_bits(11, kElephant11, {{10, kElephant10}, {9, kElephant9}}) == 11);
  // A candidate is compared with level 0's curve, not with a finer
  // candidate's, and no candidate means level 0's bits.
  CHECK(fewest_control_bits(11, kElephant11, {}) == 11);
  CHECK(fewest_control_bits(10, kArmadillo10, {{9, kArmadillo10}}) == 9);
}

}  // namespace dbss
