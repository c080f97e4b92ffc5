// The mesh-to-mesh distance and its surface samples (dbss/measure), on
// shapes whose answers are known.
#include <catch2/catch.hpp>

#include <cmath>

#include "../shapes.h"
#include "dbss/measure/mesh_distance.h"
#include "dbss/measure/surface_samples.h"

using namespace dbss;

namespace {

TriangleMesh scaled(TriangleMesh m, float s) {
  for (float& x : m.positions) x *= s;
  return m;
}

// A unit square in the plane z = height, two triangles.
TriangleMesh square(float height) {
  return {{0, 0, height, 1, 0, height, 1, 1, height, 0, 1, height}, {0, 1, 2, 0, 2, 3}};
}

}  // namespace

TEST_CASE("surface samples are reproducible, on the surface and spread by area") {
  // Two triangles side by side, areas 1/2 and 3/2.
  const TriangleMesh m{{0, 0, 0, 1, 0, 0, 0, 1, 0, 4, 0, 0}, {0, 1, 2, 1, 3, 2}};
  const auto p = sample_surface(m, 20000, 7);
  REQUIRE(p.size() == 60000);
  CHECK(p == sample_surface(m, 20000, 7));
  CHECK(p != sample_surface(m, 20000, 8));
  size_t in_first = 0;
  for (size_t i = 0; i < p.size(); i += 3) {
    CHECK(p[i + 2] == 0.0);
    REQUIRE(p[i] >= 0.0);
    REQUIRE(p[i + 1] >= 0.0);
    in_first += p[i] + p[i + 1] <= 1.0;
  }
  CHECK(std::abs(double(in_first) / 20000 - 0.25) < 0.015);
  CHECK(sample_surface(TriangleMesh{}, 10, 1).empty());
}

TEST_CASE("standard_normal has mean 0 and variance 1") {
  std::mt19937 rng(5);
  double s = 0, s2 = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double x = standard_normal(rng);
    s += x, s2 += x * x;
  }
  CHECK(std::abs(s / n) < 0.01);
  CHECK(std::abs(s2 / n - 1.0) < 0.02);
}

TEST_CASE("identical meshes are 0 apart") {
  const TriangleMesh m = test::uv_sphere(24, 48);
  const MeshDistance d = mesh_distance(m, m, {20000, 3, 1});
  CHECK(d.mean() < 1e-12);
  CHECK(d.max() < 1e-12);
}

TEST_CASE("parallel squares are their height apart, both ways") {
  const MeshDistance d = mesh_distance(square(0), square(0.25f), {4000, 1, 1});
  CHECK(d.a_to_b_mean == Approx(0.25).epsilon(1e-9));
  CHECK(d.b_to_a_mean == Approx(0.25).epsilon(1e-9));
  CHECK(d.max() == Approx(0.25).epsilon(1e-9));
}

TEST_CASE("a unit sphere and the same sphere scaled by 1.01 are about 0.01 apart") {
  const TriangleMesh m = test::uv_sphere(64, 128);
  const MeshDistance d = mesh_distance(m, scaled(m, 1.01f), {40000, 1, 2});
  // The facets sit slightly inside the unit sphere, so a little under 0.01.
  CHECK(d.mean() == Approx(0.01).epsilon(0.03));
  CHECK(d.a_to_b_mean == Approx(d.b_to_a_mean).epsilon(0.03));
  CHECK(d.max() < 0.0105);
}

TEST_CASE("the thread count does not change the distance") {
  const TriangleMesh a = test::torus(16, 12), b = scaled(test::torus(20, 10), 1.02f);
  const MeshDistance one = mesh_distance(a, b, {10000, 9, 1}), three = mesh_distance(a, b, {10000, 9, 3});
  CHECK(one.a_to_b_mean == three.a_to_b_mean);
  CHECK(one.b_to_a_mean == three.b_to_a_mean);
  CHECK(one.max() == three.max());
}

TEST_CASE("a mesh without triangles is infinitely far") {
  const MeshDistance d = mesh_distance(test::icosahedron(), TriangleMesh{}, {1000, 1, 1});
  CHECK(std::isinf(d.mean()));
}
