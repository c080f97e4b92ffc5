#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>
#include <random>

#include "../sampled_shapes.h"
#include "dbss/encoder/outliers.h"
#include "dbss/encoder/point_index.h"

using namespace dbss;

namespace {

PointCloud sphere_points(size_t n, uint32_t seed) {
  return test::sample_sdf([](double x, double y, double z) { return test::sphere_sdf(x, y, z, 0, 0, 0, 1); }, -1.2, 1.2, n,
                          seed);
}

void add(PointCloud& pc, double x, double y, double z) {
  pc.xyz.push_back(static_cast<float>(x));
  pc.xyz.push_back(static_cast<float>(y));
  pc.xyz.push_back(static_cast<float>(z));
}

// Two points are in one cluster iff a chain of points each within the radius
// of the next joins them: the same partition as union-find over all pairs.
std::vector<uint32_t> brute_force_clusters(const PointCloud& pc, double radius) {
  const size_t n = pc.size();
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(double{pc.xyz[3 * i + a]} - pc.xyz[3 * j + a], 2);
      if (d2 <= radius * radius) parent[std::max(find(uint32_t(i)), find(uint32_t(j)))] = std::min(find(uint32_t(i)), find(uint32_t(j)));
    }
  std::vector<uint32_t> id(n), root_id(n, UINT32_MAX);
  uint32_t c = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t r = find(uint32_t(i));
    if (root_id[r] == UINT32_MAX) root_id[r] = c++;
    id[i] = root_id[r];
  }
  return id;
}

}  // namespace

TEST_CASE("point clusters equal a brute-force union over all pairs within the radius") {
  // Clumps of random sizes and spreads, some closer to each other than the
  // radius, some farther: every kind of link the cell grid must find.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    PointCloud pc;
    const int clumps = 2 + trial % 7;
    for (int c = 0; c < clumps; ++c) {
      const double cx = 3 * u(rng), cy = 3 * u(rng), cz = 3 * u(rng), spread = 0.05 + 0.3 * (1 + u(rng));
      const int count = 1 + int(40 * (1 + u(rng)));
      for (int k = 0; k < count; ++k) add(pc, cx + spread * u(rng), cy + spread * u(rng), cz + spread * u(rng));
    }
    const PointIndex index(pc);
    for (double radius : {0.05, 0.2, 0.7}) {
      INFO("trial " << trial << ", radius " << radius);
      uint32_t count = 0;
      const std::vector<uint32_t> got = point_clusters(index, radius, &count);
      const std::vector<uint32_t> want = brute_force_clusters(pc, radius);
      CHECK(got == want);
      CHECK(count == *std::max_element(want.begin(), want.end()) + 1);
    }
  }
}

TEST_CASE("outliers: stray points and a far clump go, a clean sphere keeps every point, --keep-outliers keeps all") {
  const PointCloud clean = sphere_points(4000, 3);
  {
    const PointIndex index(clean);
    OutlierStats s;
    const PointCloud kept = remove_outliers(index, {}, &s);
    CHECK(kept.size() == clean.size());
    CHECK(s.isolated == 0);
    CHECK(s.cluster_points == 0);
  }
  PointCloud dirty = clean;
  // Ten lone points far outside and a clump of five at 3 radii.
  for (int k = 0; k < 10; ++k) add(dirty, 2.5 * std::cos(k), 2.5 * std::sin(k), 0.3 * k - 1.5);
  for (int k = 0; k < 5; ++k) add(dirty, 3.0 + 0.01 * k, 0.01 * k, 0);
  const PointIndex index(dirty);
  OutlierStats s;
  const PointCloud kept = remove_outliers(index, {}, &s);
  CHECK(s.points_in == dirty.size());
  CHECK(s.isolated + s.cluster_points == 15);
  CHECK(s.kept() == clean.size());
  CHECK(kept.size() == clean.size());
  // The survivors are the sphere's points, in input order.
  CHECK(std::equal(kept.xyz.begin(), kept.xyz.end(), clean.xyz.begin()));
  OutlierOptions keep_all;
  keep_all.enabled = false;
  CHECK(remove_outliers(index, keep_all, &s).size() == dirty.size());
  CHECK(s.kept() == dirty.size());
}

TEST_CASE("outliers: strays four spacings off the surface go, alone or side by side, and crease points and noise tails stay") {
  const PointCloud clean = sphere_points(6000, 5);
  const double spacing = [&] {
    const PointIndex index(clean);
    return point_spacing(index, 1, 0.5);
  }();
  PointCloud dirty = clean;
  // 20 lone strays and 5 pairs (a third of a spacing apart), each 4 median
  // spacings above the sphere: within reach of the surface points, where
  // only the off-plane test can tell them.
  std::mt19937 rng(9);
  std::normal_distribution<double> g(0.0, 1.0);
  size_t strays = 0;
  for (int k = 0; k < 25; ++k) {
    double d[3] = {g(rng), g(rng), g(rng)};
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double r = 1.0 + 4.0 * spacing;
    add(dirty, r * d[0] / len, r * d[1] / len, r * d[2] / len);
    ++strays;
    if (k >= 20) {
      add(dirty, r * d[0] / len + spacing / 3, r * d[1] / len, r * d[2] / len);
      ++strays;
    }
  }
  {
    const PointIndex index(dirty);
    OutlierStats s;
    const PointCloud kept = remove_outliers(index, {}, &s);
    // Nine in ten at least (one in a sparse patch of the sample may pass
    // for a surface point: the test is relative to the local spacing), and
    // never a surface point.
    CHECK(s.isolated >= strays * 9 / 10);
    CHECK(s.isolated <= strays);
    REQUIRE(kept.size() >= clean.size());
    CHECK(std::equal(clean.xyz.begin(), clean.xyz.end(), kept.xyz.begin()));
  }
  // A cube: points on its 12 creases and 8 corners stand off any one plane
  // of their neighbours, yet are as close to their nearest points as the
  // faces' points are.
  {
    const PointCloud cube = test::sample_sdf(
        [](double x, double y, double z) { return test::box_sdf(x, y, z, 0, 0, 0, 1, 1, 1); }, -1.2, 1.2, 6000, 5);
    const PointIndex index(cube);
    OutlierStats s;
    remove_outliers(index, {}, &s);
    INFO("cube points dropped: " << s.isolated);
    CHECK(s.isolated <= cube.size() / 1000);
  }
  // Noise of a third of a spacing: the noise's tails are not strays.
  {
    PointCloud noisy = clean;
    std::normal_distribution<double> n(0.0, spacing / 3);
    for (float& v : noisy.xyz) v = static_cast<float>(v + n(rng));
    const PointIndex index(noisy);
    OutlierStats s;
    remove_outliers(index, {}, &s);
    INFO("noisy sphere points dropped: " << s.isolated);
    CHECK(s.isolated <= noisy.size() / 200);
  }
}
