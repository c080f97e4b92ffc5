// Issue 19 (scale): the outlier stage visits points in a spatial order and
// hands its index on, and the self-check shares its distances between
// threads; none of that may change what comes out.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "../sampled_shapes.h"
#include "dbss/encoder/encode.h"
#include "dbss/encoder/outliers.h"
#include "dbss/encoder/point_index.h"

using namespace dbss;

namespace {

// A torus of 24,000 points (over the 10,000 per thread at which the outlier
// passes split) with 40 strays a little off it, one far clump, and 300 exact
// duplicates of earlier points.
PointCloud dirty_torus() {
  PointCloud pc = test::sample_sdf([](double x, double y, double z) { return test::torus_sdf(x, y, z, 0, 0, 1.0, 0.35); }, -1.5,
                                   1.5, 24000, 7);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  const auto add = [&](double x, double y, double z) {
    pc.xyz.push_back(static_cast<float>(x));
    pc.xyz.push_back(static_cast<float>(y));
    pc.xyz.push_back(static_cast<float>(z));
  };
  for (int k = 0; k < 40; ++k) add(u(rng), u(rng), 0.6 + 0.2 * std::abs(u(rng)));
  for (int k = 0; k < 6; ++k) add(2.5 + 0.01 * k, 0.0, 0.01 * k);
  for (size_t k = 0; k < 300; ++k) {
    const size_t i = k * 71 % 24000;
    add(pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]);
  }
  return pc;
}

}  // namespace

TEST_CASE("scale: the outlier stage keeps the same points on one thread and on two, and its index is over what it kept") {
  const PointCloud pc = dirty_torus();
  const PointIndex index(pc);
  OutlierOptions one, two;
  one.threads = 1;
  two.threads = 2;
  OutlierStats s1, s2;
  PointCloud kept1, kept2;
  const auto index1 = remove_outliers(index, one, &s1, kept1);
  const auto index2 = remove_outliers(index, two, &s2, kept2);
  CHECK(kept1.xyz == kept2.xyz);
  CHECK(s1.duplicates == 300);
  CHECK(s2.duplicates == 300);
  CHECK(s1.isolated == s2.isolated);
  CHECK(s1.cluster_points == s2.cluster_points);
  // Strays went (most of the 40 and the clump), and at most a few torus points.
  CHECK(s1.isolated + s1.cluster_points >= 30);
  CHECK(s1.kept() >= 24000 - 50);
  CHECK(kept1.size() == s1.kept());
  // The plain call agrees with the one handing the index out.
  CHECK(remove_outliers(index, one).xyz == kept1.xyz);
  // An index handed out answers over the points kept, as a fresh one does.
  if (index1) {
    CHECK(&index1->points() == &kept1);
    const PointIndex fresh(kept1);
    for (size_t i = 0; i < kept1.size(); i += 97) {
      const float q[3] = {kept1.xyz[3 * i] + 0.01f, kept1.xyz[3 * i + 1], kept1.xyz[3 * i + 2] - 0.01f};
      CHECK(index1->nearest(q) == fresh.nearest(q));
    }
  }
}

TEST_CASE("scale: the encoder writes the same bytes on one thread and on two, outlier stage on") {
  const PointCloud pc = dirty_torus();
  EncodeOptions o;
  o.levels = 2;
  o.threads = 1;
  auto one = encode_points(pc, o);
  o.threads = 2;
  auto two = encode_points(pc, o);
  REQUIRE(one.ok());
  REQUIRE(two.ok());
  CHECK(one.value().bytes == two.value().bytes);
  CHECK(one.value().check.points_to_surface == two.value().check.points_to_surface);
  CHECK(one.value().outliers.isolated + one.value().outliers.cluster_points > 0);
}
