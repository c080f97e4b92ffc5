// Handles through area the scan never saw (bare_handles.h, check_scan's
// `bare_handle` warning): a plate scanned with gaps on both faces where a
// real plate would have holes comes out with a handle through each gap and,
// before the check, no warning; a plate with real holes (their walls
// scanned) and clean complete scans are not warned.
#include <catch2/catch.hpp>

#include <numbers>

#include "../defect_shapes.h"
#include "../shapes.h"
#include "dbss/encoder/bare_handles.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/scan_check.h"

using namespace dbss;

// The count itself, on a torus whose vertices are given ratios by hand:
// a bare band right round the tube or right round the hole loses the one
// handle; a bare patch (a disc) loses none; a band nearer than the reach
// is not bare.
TEST_CASE("bare handles: a bare band round a torus carries its handle, a bare patch none") {
  const uint32_t rings = 24, sides = 12;
  const TriangleMesh t = test::torus(rings, sides);
  REQUIRE(mesh_info(t).genus == 1);
  const auto ratios = [&](auto bare) {
    std::vector<float> r(t.vertex_count(), 0.5f);
    for (uint32_t i = 0; i < rings; ++i)
      for (uint32_t j = 0; j < sides; ++j)
        if (bare(i, j)) r[i * sides + j] = 10.0f;
    return r;
  };
  const auto round_tube = ratios([](uint32_t i, uint32_t) { return i >= 3 && i <= 5; });
  const auto round_hole = ratios([](uint32_t, uint32_t j) { return j >= 2 && j <= 4; });
  const auto patch = ratios([](uint32_t i, uint32_t j) { return i >= 3 && i <= 5 && j >= 2 && j <= 4; });
  const auto cross = ratios([](uint32_t i, uint32_t j) { return (i >= 3 && i <= 5) || (j >= 2 && j <= 4); });
  std::vector<uint32_t> at;
  CHECK(bare_handles(t, round_tube, 4.0f, &at) == 1);
  CHECK(at.size() == 1);
  CHECK(bare_handles(t, round_hole, 4.0f) == 1);
  CHECK(bare_handles(t, patch, 4.0f) == 0);
  CHECK(bare_handles(t, cross, 4.0f) == 1);
  CHECK(bare_handles(t, round_tube, 12.0f) == 0);
}

namespace {
bool warned(const Encoding& e, const std::string& code) {
  for (const ScanWarning& w : e.check.warnings)
    if (w.code == code) return true;
  return false;
}
}  // namespace

// A plate 0.2 thick scanned with gaps on both faces where holes would be
// (scan_bench --plates): the carving bores a tunnel through each gap (genus
// 3 and 4), which was shipped with no warning.  The same plates with real
// holes, walls scanned, keep their genus and are not warned.
TEST_CASE("bare handles: tunnels through a plate's scanning gaps are warned, real holes are not") {
  constexpr double kHalf = 0.1, kRadius = 0.18;
  constexpr size_t kPoints = 8000;
  EncodeOptions o;
  o.levels = 1;
  for (int holes : {3, 4}) {
    CAPTURE(holes);
    const test::Sdf solid = [](double x, double y, double z) { return test::box_sdf(x, y, z, 0, 0, 0, 1, 0.7, kHalf); };
    const PointCloud gaps = test::with_plate_gaps(test::sample_sdf(solid, -1.1, 1.1, kPoints, 5), holes, kRadius);
    auto g = encode_points(gaps, o);
    REQUIRE(g.ok());
    CAPTURE(mesh_info(g.value().stages.control).genus, g.value().check.bare_handles, g.value().check.bare_handle_reach);
    CHECK(warned(g.value(), "bare_handle"));
    CHECK(g.value().check.bare_handles >= 1);

    const test::Shape plate = test::holed_plate(kHalf, holes, kRadius);
    const double faces = 2 * (2 * 2 * 0.7 - holes * kRadius * kRadius * std::numbers::pi);
    const double walls = holes * 2 * std::numbers::pi * kRadius * 2 * kHalf;
    const PointCloud walled = test::with_hole_walls(test::sample_sdf(plate.sdf, plate.lo, plate.hi, kPoints, 5), holes, kRadius,
                                                    kHalf, static_cast<size_t>(kPoints * walls / faces), 1005);
    auto w = encode_points(walled, o);
    REQUIRE(w.ok());
    CAPTURE(w.value().check.bare_handle_reach);
    CHECK(mesh_info(w.value().stages.control).genus == holes);
    CHECK_FALSE(warned(w.value(), "bare_handle"));
  }
}

// Complete clean scans whose sampling is very uneven (the triple torus's
// nearest-neighbour distance varies 6x from median to 99th percentile):
// no handle is bare, at 4,000 points (seed 7 came nearest on the bench, its
// handle bare at 3 local spacings) and 8,000.
TEST_CASE("bare handles: clean complete tori are not warned") {
  const test::Shape& shape = test::genus_shape("triple torus");
  for (size_t points : {size_t{4000}, size_t{8000}})
    for (uint32_t seed : {5u, 7u}) {
      const PointCloud pc = test::sample_sdf(shape.sdf, shape.lo, shape.hi, points, seed);
      EncodeOptions o;
      o.levels = 2;
      auto e = encode_points(pc, o);
      REQUIRE(e.ok());
      CAPTURE(points, seed, e.value().check.bare_handle_reach);
      CHECK_FALSE(warned(e.value(), "bare_handle"));
    }
}

// The encoder's own tubes (joined across a cut, bridged between facing
// holes) are told from bare handles by where they were built, not by their
// number: subtracting a count let tubes elsewhere hide as many bare handles
// (the 3-gap plate with three tubes recorded away from it was unwarned);
// tubes recorded on the gaps' tunnels themselves are not bare.
TEST_CASE("bare handles: the encoder's own tubes are excluded by place not by count") {
  constexpr double kHalf = 0.1, kRadius = 0.18;
  const test::Sdf solid = [](double x, double y, double z) { return test::box_sdf(x, y, z, 0, 0, 0, 1, 0.7, kHalf); };
  const PointCloud gaps = test::with_plate_gaps(test::sample_sdf(solid, -1.1, 1.1, 8000, 5), 3, kRadius);
  EncodeOptions o;
  o.levels = 1;
  auto g = encode_points(gaps, o);
  REQUIRE(g.ok());
  Encoding e = std::move(g).value();
  const PointIndex index(e.points);
  REQUIRE(e.tubes.tubes == 0);
  const uint32_t bare = e.check.bare_handles;
  REQUIRE(bare >= 1);
  // Three tubes of the encoder's own, far off the plate.
  e.tubes.tubes = 3;
  e.tubes.at = {5, 5, 5, 5.1f, 5, 5, 5.2f, 5, 5};
  const ScanCheck elsewhere = check_scan(e, index);
  CHECK(elsewhere.bare_handles == bare);
  // The same tubes recorded through every gap: points filling each gap's
  // disc across the plate, every 0.01.
  e.tubes.at.clear();
  for (const auto& c : test::plate_hole_centres(3))
    for (double x = -kRadius; x <= kRadius; x += 0.01)
      for (double y = -kRadius; y <= kRadius; y += 0.01)
        for (double z = -kHalf; z <= kHalf; z += 0.01)
          if (std::hypot(x, y) <= kRadius)
            for (double v : {c[0] + x, c[1] + y, z}) e.tubes.at.push_back(static_cast<float>(v));
  const ScanCheck through = check_scan(e, index);
  CHECK(through.bare_handles == 0);
}
