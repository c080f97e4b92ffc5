// The reconstruction stages after the sheet cut on oriented manifolds with
// boundary (a hemisphere, a disc, a tube), built here, and fingerprints of
// their output on closed meshes recorded before boundaries were handled, so
// the closed path stays bit for bit what it was.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <set>
#include <vector>

#include "../shapes.h"
#include "dbss/encoder/mesh_adjacency.h"
#include "dbss/encoder/mesh_folds.h"
#include "dbss/encoder/self_intersections.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/projection.h"
#include "dbss/encoder/shell_mesh.h"
#include "dbss/encoder/shrink_wrap.h"
#include "dbss/encoder/simplify.h"

using namespace dbss;

namespace {
constexpr double kPi = std::numbers::pi;

// Concentric rings of vertices, ring r of counts[r] vertices at `at(t, angle)`
// with t = r / (rings - 1); a ring of one vertex is a pole.  Neighbouring
// rings are stitched by walking both in angle order, so rings of different
// counts give evenly shaped triangles.
TriangleMesh rings_mesh(const std::vector<uint32_t>& counts, const std::function<std::array<double, 3>(double, double)>& at) {
  TriangleMesh m;
  std::vector<uint32_t> first;
  for (size_t r = 0; r < counts.size(); ++r) {
    first.push_back(static_cast<uint32_t>(m.vertex_count()));
    const double t = double(r) / double(counts.size() - 1);
    for (uint32_t j = 0; j < counts[r]; ++j) {
      const auto p = at(t, 2 * kPi * j / counts[r]);
      for (double x : p) m.positions.push_back(static_cast<float>(x));
    }
  }
  for (size_t r = 0; r + 1 < counts.size(); ++r) {
    const uint32_t na = counts[r], nb = counts[r + 1];
    auto a = [&](uint32_t i) { return first[r] + i % na; };
    auto b = [&](uint32_t j) { return first[r + 1] + j % nb; };
    uint32_t i = 0, j = 0;
    while (i < na || j < nb) {
      // Advance the ring whose next vertex comes first in angle; a pole never advances.
      const bool step_a = na > 1 && i < na && (j == nb || double(i + 1) / na < double(j + 1) / nb);
      if (step_a) m.triangles.insert(m.triangles.end(), {a(i), b(j), a(i + 1)}), ++i;
      else m.triangles.insert(m.triangles.end(), {a(i), b(j), b(j + 1)}), ++j;
      if (na == 1 && j == nb) break;
    }
  }
  return m;
}

// The upper unit hemisphere (pole up, rim the equator): one boundary loop.
TriangleMesh hemisphere(uint32_t rings) {
  std::vector<uint32_t> counts{1};
  for (uint32_t r = 1; r <= rings; ++r) counts.push_back(static_cast<uint32_t>(std::lround(4 * rings * std::sin(kPi / 2 * r / rings))));
  return rings_mesh(counts, [](double t, double a) {
    const double th = kPi / 2 * t;
    return std::array<double, 3>{std::sin(th) * std::cos(a), std::sin(th) * std::sin(a), std::cos(th)};
  });
}

// The unit disc in z = 0 (facing +z): one boundary loop.
TriangleMesh disc(uint32_t rings, float z = 0) {
  std::vector<uint32_t> counts{1};
  for (uint32_t r = 1; r <= rings; ++r) counts.push_back(6 * r);
  return rings_mesh(counts, [z](double t, double a) { return std::array<double, 3>{t * std::cos(a), t * std::sin(a), z}; });
}

// An open unit cylinder from z = 0 to z = height: two boundary loops.
TriangleMesh tube(uint32_t rings, uint32_t sides, double height) {
  return rings_mesh(std::vector<uint32_t>(rings, sides), [height](double t, double a) {
    return std::array<double, 3>{std::cos(a), std::sin(a), height * t};
  });
}

// Vertices on an edge with one triangle.
std::vector<uint32_t> rim_vertices(const TriangleMesh& m) {
  std::set<std::pair<uint32_t, uint32_t>> half;
  for (size_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) half.insert({m.triangles[3 * f + k], m.triangles[3 * f + (k + 1) % 3]});
  std::set<uint32_t> rim;
  for (const auto& [a, b] : half)
    if (!half.count({b, a})) rim.insert({a, b});
  return {rim.begin(), rim.end()};
}

// Distance of p from the circle of radius 1 about the z axis at height h.
double from_circle(const float* p, double h) { return std::hypot(std::hypot(p[0], p[1]) - 1, p[2] - h); }

uint64_t fnv1a(const TriangleMesh& m) {
  uint64_t h = 1469598103934665603ull;
  auto eat = [&](const void* data, size_t bytes) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h = (h ^ c[i]) * 1099511628211ull;
  };
  eat(m.positions.data(), m.positions.size() * sizeof(float));
  eat(m.triangles.data(), m.triangles.size() * sizeof(uint32_t));
  return h;
}

// Evenly spread points on the unit sphere (a Fibonacci spiral).
PointCloud sphere_points(size_t n) {
  PointCloud pc;
  for (size_t i = 0; i < n; ++i) {
    const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), a = i * kPi * (3 - std::sqrt(5.0));
    pc.xyz.insert(pc.xyz.end(), {float(r * std::cos(a)), float(r * std::sin(a)), float(z)});
  }
  return pc;
}

TriangleMesh scaled(TriangleMesh m, float s) {
  for (float& x : m.positions) x *= s;
  return m;
}
}  // namespace

TEST_CASE("closed meshes: simplify, shrink-wrap, untangle, relax and projection give the recorded bits") {
  // Fingerprints taken with the code before boundaries were handled.
  const auto simplified = simplify_mesh(test::jitter(test::torus(48, 24), 0.01f), 300);
  REQUIRE(simplified.ok());
  CHECK(simplified.value().triangle_count() == 300);

  const PointCloud pc = sphere_points(4000);
  const PointIndex index(pc);
  TriangleMesh wrapped = test::jitter(scaled(test::uv_sphere(24, 48), 1.2f), 0.01f);
  shrink_wrap(wrapped, index);

  TriangleMesh folded = test::jitter(test::uv_sphere(16, 32), 0.15f, 3);
  REQUIRE(count_foldovers(folded) > 0);
  untangle_folds(folded);

  TriangleMesh crossed = test::torus(32, 16);
  for (int a = 0; a < 3; ++a) crossed.positions[a] = -crossed.positions[a] * 1.1f;  // through the far side
  REQUIRE(count_self_intersections(crossed) > 0);
  relax_self_intersections(crossed);

  TriangleMesh projected = test::jitter(scaled(test::uv_sphere(12, 24), 1.05f), 0.01f);
  project_to_points(projected, index);

  CHECK(fnv1a(simplified.value()) == 9413455603625366776ull);
  CHECK(fnv1a(wrapped) == 14233213347156765746ull);
  CHECK(fnv1a(folded) == 17517505674473230670ull);
  CHECK(fnv1a(crossed) == 17770200193454856742ull);
  CHECK(fnv1a(projected) == 3253195008229181974ull);
}

TEST_CASE("mesh_info counts boundary loops and gives the genus of open surfaces") {
  struct Want {
    const char* name;
    TriangleMesh mesh;
    uint32_t components, loops;
    int64_t euler, genus;
  };
  TriangleMesh two = disc(6);  // a disc and a sphere side by side
  const TriangleMesh ball = test::uv_sphere(6, 12);
  const uint32_t base = static_cast<uint32_t>(two.vertex_count());
  for (size_t i = 0; i < ball.positions.size(); ++i) two.positions.push_back(ball.positions[i] + (i % 3 == 0 ? 3.0f : 0.0f));
  for (uint32_t v : ball.triangles) two.triangles.push_back(base + v);
  const Want cases[] = {
      {"disc", disc(8), 1, 1, 1, 0},
      {"hemisphere", hemisphere(8), 1, 1, 1, 0},
      {"tube", tube(6, 24, 1.0), 1, 2, 0, 0},
      {"closed sphere", test::uv_sphere(8, 16), 1, 0, 2, 0},
      {"closed torus", test::torus(16, 8), 1, 0, 0, 1},
      {"disc and sphere", two, 2, 1, 3, 0},
  };
  for (const auto& c : cases) {
    INFO(c.name);
    const MeshInfo i = mesh_info(c.mesh);
    CHECK(i.manifold);
    CHECK(i.closed == (c.loops == 0));
    CHECK(i.components == c.components);
    CHECK(i.boundary_loops == c.loops);
    CHECK(i.euler == c.euler);
    CHECK(i.genus == c.genus);
  }
}

TEST_CASE("simplify_mesh keeps the topology and the rim of open surfaces") {
  struct Case {
    const char* name;
    TriangleMesh mesh;
    std::vector<double> rim_heights;  // the rim circles (radius 1) lie at these z
    bool on_sphere;
  };
  const Case cases[] = {
      {"hemisphere", hemisphere(24), {0.0}, true},
      {"disc", disc(20), {0.0}, false},
      {"tube", tube(20, 48, 2.0), {0.0, 2.0}, false},
  };
  for (const auto& c : cases) {
    INFO(c.name);
    const MeshInfo before = mesh_info(c.mesh);
    REQUIRE(before.manifold);
    const uint32_t target = static_cast<uint32_t>(c.mesh.triangle_count() / 10);
    const auto out = simplify_mesh(c.mesh, target);
    REQUIRE(out.ok());
    const TriangleMesh& m = out.value();
    // One triangle per rim collapse, two per inner one: the target +-1.
    CHECK(m.triangle_count() + 1 >= target);
    CHECK(m.triangle_count() <= target + 1);
    const MeshInfo after = mesh_info(m);
    CHECK(after.manifold);
    CHECK(after.components == before.components);
    CHECK(after.euler == before.euler);
    CHECK(after.boundary_loops == before.boundary_loops);
    CHECK(after.genus == before.genus);
    double worst_rim = 0, worst_sphere = 0;
    for (uint32_t v : rim_vertices(m)) {
      double d = 1e9;
      for (double h : c.rim_heights) d = std::min(d, from_circle(&m.positions[3 * size_t{v}], h));
      worst_rim = std::max(worst_rim, d);
    }
    for (size_t v = 0; v < m.vertex_count() && c.on_sphere; ++v) {
      const float* p = &m.positions[3 * v];
      worst_sphere = std::max(worst_sphere, std::abs(std::sqrt(double{p[0]} * p[0] + double{p[1]} * p[1] + double{p[2]} * p[2]) - 1));
    }
    CHECK(worst_rim < 0.02);
    CHECK(worst_sphere < 0.02);
    CHECK(count_foldovers(m) == 0);
  }
}

TEST_CASE("simplify_mesh on a strip of rim vertices only collapses along the rim") {
  // Every inner edge of a one-quad-wide strip joins two rim vertices: a
  // collapse there would pinch the strip, so it only shortens along its length.
  const TriangleMesh strip = test::planar_grid(30, 1);
  const auto out = simplify_mesh(strip, 2);
  REQUIRE(out.ok());
  const MeshInfo i = mesh_info(out.value());
  CHECK(i.manifold);
  CHECK(i.components == 1);
  CHECK(i.euler == 1);
  CHECK(i.boundary_loops == 1);
  CHECK(out.value().triangle_count() < strip.triangle_count());
  // The strip's corners stay (every collapse lands on the rim, and its
  // straight long sides keep their line).
  for (size_t v = 0; v < out.value().vertex_count(); ++v) {
    const float y = out.value().positions[3 * v + 1], z = out.value().positions[3 * v + 2];
    CHECK(z == 0.0f);
    CHECK((std::abs(y) < 1e-4f || std::abs(y - 1) < 1e-4f));
  }
}

TEST_CASE("shrink_wrap keeps the rim of an open disc on the points") {
  // Points on the unit disc, a jittered grid of spacing s; the mesh starts
  // a little above them.
  const double s = 0.02;
  PointCloud pc;
  uint32_t seed = 5;
  auto noise = [&] {
    seed = seed * 1664525u + 1013904223u;
    return (static_cast<double>(seed >> 8) / 16777216.0 - 0.5) * 0.5 * s;
  };
  for (double x = -1; x <= 1; x += s)
    for (double y = -1; y <= 1; y += s) {
      const double px = x + noise(), py = y + noise();
      if (std::hypot(px, py) <= 1) pc.xyz.insert(pc.xyz.end(), {float(px), float(py), 0.0f});
    }
  const PointIndex index(pc);
  TriangleMesh m = disc(16, 0.05f);
  shrink_wrap(m, index);
  const auto rim = rim_vertices(m);
  REQUIRE(rim.size() == 6 * 16);
  double inward = 0;
  for (uint32_t v : rim) inward = std::max(inward, 1 - std::hypot(double{m.positions[3 * size_t{v}]}, double{m.positions[3 * size_t{v} + 1]}));
  CHECK(inward < 3 * s);
  for (size_t v = 0; v < m.vertex_count(); ++v) CHECK(std::abs(m.positions[3 * v + 2]) < 0.01f);
  CHECK(mesh_info(m).manifold);
  CHECK(count_foldovers(m) == 0);
}

TEST_CASE("untangle_folds and count_foldovers see no fold on an open hemisphere and keep a disc's rim") {
  TriangleMesh h = hemisphere(12);
  const TriangleMesh before = h;
  CHECK(count_foldovers(h) == 0);
  CHECK(foldover_vertices(h).empty());
  CHECK(untangle_folds(h) == 0);
  CHECK(h == before);
  const Adjacency vt = vertex_triangles(h);
  for (uint32_t v = 0; v < h.vertex_count(); ++v) CHECK_FALSE(folded_around(h, vt, v));

  // A disc with an inner vertex next to the rim thrown across its
  // neighbours: folds next to the rim, which untangling must not pull in.
  TriangleMesh d = disc(10);
  const auto rim = rim_vertices(d);
  const uint32_t inner = static_cast<uint32_t>(d.vertex_count() - 6 * 10 - 1);  // last vertex of ring 9
  const float* p = &d.positions[3 * size_t{inner}];
  const float to[3] = {-0.6f * p[0], -0.6f * p[1], -0.05f};
  for (int a = 0; a < 3; ++a) d.positions[3 * size_t{inner} + a] = to[a];
  REQUIRE(count_foldovers(d) > 0);
  untangle_folds(d);
  for (uint32_t v : rim) CHECK(from_circle(&d.positions[3 * size_t{v}], 0) < 0.02);
}

TEST_CASE("relax_self_intersections moves rim vertices along the rim only") {
  // A tube's vertex next to the rim dragged through the far wall: its
  // triangles, some with rim corners, cross the wall's, some with rim
  // corners too.  Smoothed towards all their neighbours, those rim corners
  // would follow the dragged vertex into the tube.
  TriangleMesh t = tube(12, 48, 1.0);
  const auto rim = rim_vertices(t);
  const uint32_t dragged = 48;  // (1, 0, 1/11), first vertex of the second ring
  t.positions[3 * dragged] = -1.3f;
  REQUIRE(count_self_intersections(t) > 0);
  CHECK(relax_self_intersections(t) > 0);
  CHECK(count_self_intersections(t) == 0);
  for (uint32_t v : rim) {
    INFO("vertex " << v);
    const float* q = &t.positions[3 * size_t{v}];
    CHECK(std::min(from_circle(q, 0), from_circle(q, 1)) < 0.02);
  }
}

TEST_CASE("project_to_points keeps an open hemisphere's rim on its points") {
  const PointCloud all = sphere_points(6000);
  PointCloud upper;
  for (size_t i = 0; i < all.size(); ++i)
    if (all.xyz[3 * i + 2] >= 0) upper.xyz.insert(upper.xyz.end(), {all.xyz[3 * i], all.xyz[3 * i + 1], all.xyz[3 * i + 2]});
  const PointIndex index(upper);
  TriangleMesh m = scaled(hemisphere(10), 1.03f);
  CHECK(project_to_points(m, index) == 0);
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    const float* p = &m.positions[3 * v];
    CHECK(std::abs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1) < 1e-3);
  }
  for (uint32_t v : rim_vertices(m)) CHECK(from_circle(&m.positions[3 * size_t{v}], 0) < 0.05);
  CHECK(count_foldovers(m) == 0);
}
