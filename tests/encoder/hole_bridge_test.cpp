// Closing holes: two ends of a tube the scan cut through are joined by a
// tube (the handle kept); holes that only face each other through the
// inside, or a lone hole, are capped.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "dbss/encoder/mesh_info.h"
#include "dbss/encoder/open_surface.h"
#include "dbss/encoder/self_intersections.h"
#include "../shapes.h"

using namespace dbss;

namespace {

// The mesh without the triangles `drop` picks (by centroid), vertices
// renumbered so none is left unused.
TriangleMesh without(const TriangleMesh& m, const std::function<bool(const double*)>& drop) {
  TriangleMesh out;
  std::vector<uint32_t> id(m.vertex_count(), UINT32_MAX);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    double c[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) c[a] += m.positions[3 * m.triangles[3 * t + k] + a] / 3.0;
    if (drop(c)) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m.triangles[3 * t + k];
      if (id[v] == UINT32_MAX) {
        id[v] = static_cast<uint32_t>(out.vertex_count());
        out.positions.insert(out.positions.end(), &m.positions[3 * v], &m.positions[3 * v] + 3);
      }
      out.triangles.push_back(id[v]);
    }
  }
  return out;
}

constexpr float kMajor = 1.0f, kMinor = 0.4f;

// A torus (major radius 1, minor 0.4) with a band of `degrees` cut out of
// its ring round the +x axis: two boundary loops facing each other (clean
// rings of the torus when `degrees` is a multiple of 15: both triangles of
// every quad go).
TriangleMesh cut_torus(double degrees) {
  const TriangleMesh t = test::torus(48, 16, kMajor, kMinor);
  const double half = degrees / 2 * std::numbers::pi / 180;
  return without(t, [&](const double* c) { return std::abs(std::atan2(c[1], c[0])) < half; });
}

}  // namespace

TEST_CASE("the two ends of a tube cut through are joined by a tube and the handle is kept") {
  for (double degrees : {30.0, 60.0, 90.0}) {
    INFO(degrees << " degrees of the ring cut out");
    TriangleMesh m = cut_torus(degrees);
    const MeshInfo cut = mesh_info(m);
    REQUIRE(cut.manifold);
    REQUIRE(cut.boundary_loops == 2);
    REQUIRE(cut.genus == 0);  // a tube: the handle is gone
    const size_t vertices_before = m.vertex_count();
    const double edge = 2 * std::numbers::pi * kMajor / 48;
    const HoleFill f = fill_holes(m, edge, 1e300, /*bridge=*/true);
    CHECK(f.bridges == 1);
    CHECK(f.doubtful_pairs == 0);  // the pair was joined
    CHECK(f.loops == 2);
    const MeshInfo closed = mesh_info(m);
    CHECK(closed.manifold);
    CHECK(closed.closed);
    CHECK(closed.components == 1);
    CHECK(closed.genus == 1);
    CHECK(count_self_intersections(m) == 0);
    // The tube continues the torus: its vertices lie near the tube's
    // surface (a straight tube across a 60-degree gap would be 0.13 inside
    // the ring's centre circle at its middle, a cap far more).
    REQUIRE(f.added_vertices.size() > 0);
    CHECK(m.vertex_count() == vertices_before + f.added_vertices.size());
    double worst = 0;
    for (uint32_t v : f.added_vertices) {
      const float* p = &m.positions[3 * v];
      const double ring = std::hypot(p[0], p[1]) - kMajor;
      worst = std::max(worst, std::abs(std::hypot(ring, double{p[2]}) - kMinor));
    }
    INFO("farthest tube vertex off the torus: " << worst);
    CHECK(worst < 0.25 * kMinor);

    // Capping each end instead loses the handle, which is why the tube.
    TriangleMesh capped = cut_torus(degrees);
    const HoleFill c = fill_holes(capped, edge);
    CHECK(c.bridges == 0);
    CHECK(mesh_info(capped).genus == 0);
  }
}

TEST_CASE("holes that face each other through the inside, or a lone hole, are capped, not joined") {
  const TriangleMesh sphere = test::uv_sphere(24, 32);
  const double edge = std::numbers::pi / 25;
  SECTION("two polar holes") {
    // Their loops face each other across the sphere's inside, as the two
    // ends of a can do, or holes on the two sides of a plate.
    TriangleMesh m = without(sphere, [](const double* c) { return std::abs(c[2]) > 0.8; });
    REQUIRE(mesh_info(m).boundary_loops == 2);
    const HoleFill f = fill_holes(m, edge, 1e300, true);
    CHECK(f.bridges == 0);
    CHECK(f.doubtful_pairs == 0);  // their axes point at each other: nothing like a cut tube
    CHECK(f.loops == 2);
    const MeshInfo i = mesh_info(m);
    CHECK(i.closed);
    CHECK(i.genus == 0);
  }
  SECTION("one hole") {
    TriangleMesh m = without(sphere, [](const double* c) { return c[0] > 0.7; });
    REQUIRE(mesh_info(m).boundary_loops == 1);
    const HoleFill f = fill_holes(m, edge, 1e300, true);
    CHECK(f.bridges == 0);
    CHECK(f.loops == 1);
    CHECK(mesh_info(m).genus == 0);
    CHECK(mesh_info(m).closed);
  }
  SECTION("two holes side by side") {
    // Beside each other on one side, their axes parallel: not facing.
    TriangleMesh m = without(sphere, [](const double* c) {
      return (c[0] > 0.85 && c[1] > 0.2) || (c[0] > 0.85 && c[1] < -0.2);
    });
    REQUIRE(mesh_info(m).boundary_loops == 2);
    const HoleFill f = fill_holes(m, edge, 1e300, true);
    CHECK(f.bridges == 0);
    CHECK(f.doubtful_pairs == 0);
    CHECK(mesh_info(m).genus == 0);
  }
}
