// The point path's control choice (encoder/src/control_choice.h): on a
// noisy cloud the crossing level's distance to the points does not veto the
// quarter mesh; on a clean cloud every level is a target, as before.
#include <catch2/catch.hpp>

#include <vector>

#include "../../encoder/src/control_choice.h"

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

}  // namespace dbss
