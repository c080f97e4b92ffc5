// Rims where a scan's points end (point_rims.h): found from the points
// alone, paired when they look like a cut tube's two ends, and the inside
// test that tells a joined pair from a capped one.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "dbss/encoder/point_rims.h"
#include "../defect_shapes.h"
#include "../shapes.h"

using namespace dbss;
namespace dt = dbss::test;

namespace {

// The ring torus of the genus shapes (R = 1, r = 0.35, round the z axis).
const dt::Shape& torus_shape() {
  static const std::vector<dt::Shape> shapes = dt::genus_shapes();
  return *dt::find_shape(shapes, "torus");
}

// The torus's points without a band right round its tube: the points whose
// angle round the z axis is within `half_width` of +x.
PointCloud cut_torus(double half_width) {
  const dt::Shape& s = torus_shape();
  const PointCloud c = dt::sample_sdf(s.sdf, s.lo, s.hi, 8000, 5);
  return dt::keep_points(c, [&](size_t i) { return std::abs(std::atan2(c.xyz[3 * i + 1], c.xyz[3 * i])) > half_width; });
}

}  // namespace

TEST_CASE("point rims: a complete torus and a complete sphere have none") {
  const dt::Shape& s = torus_shape();
  const PointCloud torus = dt::sample_sdf(s.sdf, s.lo, s.hi, 8000, 5);
  CHECK(find_point_rims(PointIndex(torus)).empty());
  const std::vector<dt::Shape> shapes = dt::genus_shapes();
  const dt::Shape& sphere = *dt::find_shape(shapes, "sphere");
  const PointCloud ball = dt::sample_sdf(sphere.sdf, sphere.lo, sphere.hi, 6000, 3);
  CHECK(find_point_rims(PointIndex(ball)).empty());
}

TEST_CASE("point rims: a band cut round a torus's tube leaves two facing rims the size of the tube") {
  const PointCloud c = cut_torus(0.35);
  const std::vector<PointRim> rims = find_point_rims(PointIndex(c));
  REQUIRE(rims.size() == 2);
  for (const PointRim& r : rims) {
    INFO("rim at " << r.centre[0] << " " << r.centre[1] << " " << r.centre[2] << ", radius " << r.radius << ", wall "
                   << r.wall);
    // The tube's cross-section: radius 0.35, centred on the ring (radius 1)
    // at the band's edges, the surface along the axis (a tube's wall).
    CHECK(r.radius == Approx(0.35).epsilon(0.3));
    CHECK(std::hypot(r.centre[0], r.centre[1]) == Approx(1.0).epsilon(0.15));
    CHECK(std::abs(r.centre[2]) < 0.1);
    CHECK(r.wall < 0.4);
    // The axis points away from the band: round the ring, away from +x.
    const double along = -r.centre[1] * r.axis[0] + r.centre[0] * r.axis[1];  // component along the ring's direction
    CHECK(along * r.centre[1] > 0);
  }
  const auto pairs = tube_end_pairs(rims);
  REQUIRE(pairs.size() == 1);
  // The torus itself joins them (the band's middle is inside its tube); a
  // surface that capped the ends (here: a small ball elsewhere) does not.
  CHECK(surface_joins(dt::torus(96, 48, 1.0f, 0.35f), rims[pairs[0].first], rims[pairs[0].second]));
  TriangleMesh ball = dt::uv_sphere(16, 32);
  for (size_t i = 0; i < ball.positions.size(); ++i) ball.positions[i] = 0.2f * ball.positions[i] - (i % 3 == 0 ? 1.0f : 0.0f);
  CHECK_FALSE(surface_joins(ball, rims[pairs[0].first], rims[pairs[0].second]));
}

TEST_CASE("point rims: a cap cut off a sphere leaves one rim, a hole in a wall, and no pair") {
  const std::vector<dt::Shape> shapes = dt::genus_shapes();
  const dt::Shape& sphere = *dt::find_shape(shapes, "sphere");
  const PointCloud ball = dt::sample_sdf(sphere.sdf, sphere.lo, sphere.hi, 6000, 3);
  const PointCloud c = dt::keep_points(ball, [&](size_t i) { return ball.xyz[3 * i + 2] < 0.7f; });
  const std::vector<PointRim> rims = find_point_rims(PointIndex(c));
  REQUIRE(rims.size() == 1);
  CHECK(rims[0].radius == Approx(std::sqrt(1 - 0.49)).epsilon(0.2));
  CHECK(rims[0].wall > 0.55);
  CHECK(rims[0].axis[2] < -0.9);  // away from the opening at the top
  CHECK(tube_end_pairs(rims).empty());
}
