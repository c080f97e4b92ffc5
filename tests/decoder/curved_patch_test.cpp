// Stencils, normals and displacement on a small curved patch, against values
// worked out by hand from spec/decoding.md (sections 5-7), and the
// crack-free property against the boundary curve's own four-point
// subdivision.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <set>

#include "../shapes.h"
#include "dbss/decoder/level_refiner.h"
#include "normals.h"
#include "dbss/decoder/topology.h"
#include "reference.h"

using namespace dbss;

namespace {

// One level by the spec's reference decoder (spec/reference): q empty for
// plain subdivision.
std::vector<float> ref_step(const TriangleMesh& m, std::span<const int32_t> q = {}, float step = 0) {
  return dbss_ref::subdivide(dbss_ref::Mesh{m.positions, m.triangles, {}, {}}, q, step).positions;
}

// The 5x5 vertex lattice x, y in -2..2, quad (x, y) split along its
// (x,y)-(x+1,y+1) diagonal (interior valence 6), lifted onto the paraboloid
//   z = (x^2 + y^2) / 8 + y / 8.
// Every coordinate, and every stencil sum below, is a small dyadic number,
// so binary64 evaluates the spec's sums exactly.
TriangleMesh paraboloid_patch() {
  TriangleMesh m;
  auto id = [](int x, int y) { return static_cast<uint32_t>((y + 2) * 5 + (x + 2)); };
  for (int y = -2; y <= 2; ++y)
    for (int x = -2; x <= 2; ++x)
      m.positions.insert(m.positions.end(), {float(x), float(y), float(x * x + y * y + y) / 8.0f});
  for (int y = -2; y < 2; ++y)
    for (int x = -2; x < 2; ++x) {
      m.triangles.insert(m.triangles.end(), {id(x, y), id(x + 1, y), id(x + 1, y + 1)});
      m.triangles.insert(m.triangles.end(), {id(x, y), id(x + 1, y + 1), id(x, y + 1)});
    }
  return m;
}

LevelTopology topology_of(const TriangleMesh& m) {
  auto t = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
  REQUIRE(t.ok());
  return std::move(t).value();
}

// The odd vertex (index into the odd vertices) whose undisplaced point has
// these x, y.
uint32_t odd_at(const std::vector<float>& level1, uint32_t evens, float x, float y) {
  for (uint32_t v = evens; v < level1.size() / 3; ++v)
    if (level1[3 * v] == x && level1[3 * v + 1] == y) return v - evens;
  FAIL("no odd vertex at " << x << " " << y);
  return 0;
}

// Hand-computed values, z in units of 1/32 where helpful.
//
// Interior edge u = (0,0), w = (1,0) (both ends valence 6), triangles
// (u, w, c = (1,1)) and (w, u, d = (0,-1)); wings (2,1), (0,1), (-1,-1),
// (1,-1).  With Z = 32 z = 4(x^2 + y^2) + 4y:
//   Z: u 0, w 4, c 12, d 0; wings 24, 8, 4, 4
//   Z(m) = (0 + 4)/2 + (12 + 0)/8 - (24 + 8 + 4 + 4)/16 = 2 + 1.5 - 2.5 = 1
// so m = (0.5, 0, 1/32), the paraboloid's own value (the regular rule is
// exact on quadratics).  Its ring (section 6): m_cu = (0.5, 0.5, 4/32),
// u, m_ud = (0, -0.5, -1/32), m_dw = (0.5, -0.5, 0), w = (1, 0, 4/32),
// m_wc = (1, 0.5, 7/32); d_i = r_i - m, with Z in 1/32:
//   d0 = (0, .5, 3), d1 = (-.5, 0, -1), d2 = (-.5, -.5, -2),
//   d3 = (0, -.5, -1), d4 = (.5, 0, 3), d5 = (.5, .5, 6)
// cross products of (d0,d1) .. (d5,d0), x and y in 1/32, z plain:
//   x: -.5 -.5 -.5 -1.5 -1.5 -1.5 = -6   -> N.x = -6/32
//   y: -1.5 -.5 -.5 -.5 -1.5 -1.5 = -6   -> N.y = -6/32
//   z: six times .25                     -> N.z = 1.5
// N = (-3/16, -3/16, 3/2), parallel to the paraboloid's normal
// (-z_x, -z_y, 1) = (-1/8, -1/8, 1) at (0.5, 0); |N|^2 = 594/256.
constexpr float kM[3] = {0.5f, 0.0f, 1.0f / 32};
constexpr float kRing[4][3] = {{0.5f, 0.5f, 4.0f / 32}, {0.0f, -0.5f, -1.0f / 32}, {0.5f, -0.5f, 0.0f}, {1.0f, 0.5f, 7.0f / 32}};
std::array<double, 3> hand_normal() {
  const double len = std::sqrt((9.0 / 256 + 9.0 / 256) + 9.0 / 4);
  const double inv = 1.0 / len;
  return {-3.0 / 16 * inv, -3.0 / 16 * inv, 1.5 * inv};
}

}  // namespace

TEST_CASE("curved patch: stencil points, the ring normal and a displacement match the hand-computed values") {
  const TriangleMesh m = paraboloid_patch();
  const LevelTopology t = topology_of(m);
  const std::vector<float> flat = ref_step(m);
  const uint32_t e = odd_at(flat, t.vertex_count, 0.5f, 0.0f);
  CHECK(flat[3 * (t.vertex_count + e) + 2] == kM[2]);
  for (const auto& r : {kRing[0], kRing[1], kRing[2], kRing[3]}) {
    const uint32_t o = odd_at(flat, t.vertex_count, r[0], r[1]);
    CHECK(flat[3 * (t.vertex_count + o) + 2] == r[2]);
  }

  // Section 6 through the decoder's ring table and normal kernel.
  const std::array<double, 3> n = hand_normal();
  double got[3];
  const std::vector<uint32_t> rings = build_odd_rings(t);
  odd_normals(rings.data(), flat.data(), t.vertex_count, e, e + 1, got);
  CHECK(got[0] == n[0]);
  CHECK(got[1] == n[1]);
  CHECK(got[2] == n[2]);
  // ... which is the paraboloid's unit normal (-1, -1, 8) / sqrt(66).
  CHECK(n[0] == Approx(-1 / std::sqrt(66.0)).epsilon(1e-15));
  CHECK(n[2] == Approx(8 / std::sqrt(66.0)).epsilon(1e-15));

  // Section 7: q = 5, step 1/64 moves m by 5/64 along n, every other odd
  // vertex stays.
  const float step = 1.0f / 64;
  std::vector<int32_t> q(t.edge_count(), 0);
  q[e] = 5;
  const std::vector<float> moved = ref_step(m, q, step);
  const double dq = 5.0 / 64;
  const float want[3] = {static_cast<float>(0.5 + dq * n[0]), static_cast<float>(0.0 + dq * n[1]),
                         static_cast<float>(1.0 / 32 + dq * n[2])};
  for (int a = 0; a < 3; ++a) CHECK(moved[3 * (t.vertex_count + e) + a] == want[a]);
  for (size_t i = 0; i < flat.size(); ++i)
    if (i / 3 != t.vertex_count + e) REQUIRE(moved[i] == flat[i]);
  // Against the analytic point, to binary32 precision.
  CHECK(want[0] == Approx(0.5 - dq / std::sqrt(66.0)).margin(1e-7));
  CHECK(want[1] == Approx(-dq / std::sqrt(66.0)).margin(1e-7));
  CHECK(want[2] == Approx(1.0 / 32 + 8 * dq / std::sqrt(66.0)).margin(1e-7));

  // The encoder's closed loop (the fast kernels) sees the same point and
  // normal and places the vertex at the same bits.
  auto refiner = LevelRefiner::create(m);
  REQUIRE(refiner.ok());
  double seen_point[3] = {0, 0, 0}, seen_normal[3] = {0, 0, 0};
  const OddChooser choose = [&](uint32_t odd, const double p[3], const double nn[3], const float*, const float*) {
    if (odd != e) return int32_t{0};
    for (int a = 0; a < 3; ++a) seen_point[a] = p[a], seen_normal[a] = nn[a];
    return int32_t{5};
  };
  std::vector<int32_t> chosen;
  refiner.value().refine(choose, step, chosen, 1);
  for (int a = 0; a < 3; ++a) {
    CHECK(seen_point[a] == kM[a]);
    CHECK(seen_normal[a] == n[a]);
    CHECK(refiner.value().positions()[3 * (t.vertex_count + e) + a] == want[a]);
  }
}

TEST_CASE("curved patch: the boundary four-point rule and the reflected wings give the hand-computed points") {
  const TriangleMesh m = paraboloid_patch();
  const LevelTopology t = topology_of(m);
  const std::vector<float> flat = ref_step(m);
  // Boundary edge (0,-2)-(1,-2), section 5.1: b = (-1,-2), a = (2,-2); on
  // the row y = -2, Z = 4x^2 + 8: b 12, u 8, w 12, a 24, so
  //   Z = (-12 + 9 * 8 + 9 * 12 - 24) / 16 = 9,
  // the curve's own value at x = 0.5 (the four-point rule is exact on
  // cubics); x and y come out as the midpoint.
  const uint32_t b = odd_at(flat, t.vertex_count, 0.5f, -2.0f);
  CHECK(flat[3 * (t.vertex_count + b) + 2] == 9.0f / 32);
  // Interior edge u = (0,-2) (boundary end, treated as regular), w = (0,-1),
  // c = (-1,-2), d = (1,-1); wings across w->c: (-1,-1); across c->u: none,
  // reflected as (-1,-2) + (0,-2) - w; across u->d: (1,-2); across d->w:
  // (1,0).  Z: u 8, w 0, c 12, d 4, wings 4, (12 + 8 - 0), 12, 4:
  //   Z = (8 + 0)/2 + (12 + 4)/8 - 4/16 - (12 + 8)/16 + 0/16 - 12/16 - 4/16
  //     = 4 + 2 - 0.25 - 1.25 - 0.75 - 0.25 = 3.5
  // (the paraboloid has 3 there: the reflection is only linear-exact), and
  // x, y come out as the midpoint (0, -1.5).
  const uint32_t r = odd_at(flat, t.vertex_count, 0.0f, -1.5f);
  CHECK(flat[3 * (t.vertex_count + r) + 2] == 3.5f / 32);
}

TEST_CASE("bordered meshes are crack-free: each cap's border is the four-point subdivision of the shared border polygon") {
  // The sphere of the crack-free test, cut along its equator ring (ring 3 of
  // uv_sphere(7, 12)) into two bordered caps.  A cap's border after three
  // levels must be exactly the border polygon subdivided on its own by the
  // four-point rule (section 5.1), evaluated here on the 12-gon alone.
  const TriangleMesh sphere = test::jitter(test::uv_sphere(7, 12), 0.03f);
  std::vector<std::array<float, 3>> ring;
  for (uint32_t j = 0; j < 12; ++j) {
    const float* p = &sphere.positions[3 * (3 * 12 + j)];
    ring.push_back({p[0], p[1], p[2]});
  }
  for (int level = 0; level < 3; ++level) {
    const size_t k = ring.size();
    std::vector<std::array<float, 3>> next;
    for (size_t j = 0; j < k; ++j) {
      const auto &b = ring[(j + k - 1) % k], &u = ring[j], &w = ring[(j + 1) % k], &a = ring[(j + 2) % k];
      std::array<float, 3> mid;
      for (int c = 0; c < 3; ++c) {
        double s = 0;
        s = s + -1.0 / 16 * b[c];
        s = s + 9.0 / 16 * u[c];
        s = s + 9.0 / 16 * w[c];
        s = s + -1.0 / 16 * a[c];
        mid[c] = static_cast<float>(s);
      }
      next.push_back(u);
      next.push_back(mid);
    }
    ring = std::move(next);
  }
  const std::set<std::array<float, 3>> expected(ring.begin(), ring.end());
  REQUIRE(expected.size() == 96);

  for (int cap = 0; cap < 2; ++cap) {
    INFO("cap " << cap);
    TriangleMesh m;
    std::vector<uint32_t> remap(sphere.vertex_count(), kNoHalfEdge);
    for (size_t f = 0; f < sphere.triangle_count(); ++f) {
      double z = 0;
      for (int k = 0; k < 3; ++k) z += sphere.positions[3 * sphere.triangles[3 * f + k] + 2];
      if ((z > 0) != (cap == 0)) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = sphere.triangles[3 * f + k];
        if (remap[v] == kNoHalfEdge) {
          remap[v] = static_cast<uint32_t>(m.vertex_count());
          m.positions.insert(m.positions.end(), &sphere.positions[3 * v], &sphere.positions[3 * v + 3]);
        }
        m.triangles.push_back(remap[v]);
      }
    }
    LevelTopology t = topology_of(m);
    std::vector<float> pos = m.positions;
    for (int level = 0; level < 3; ++level) {
      pos = ref_step(TriangleMesh{pos, t.triangles});
      t = refine_topology(t);
    }
    std::set<std::array<float, 3>> border;
    for (uint32_t v = 0; v < t.vertex_count; ++v)
      if (t.vertex_boundary[v]) border.insert({pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]});
    CHECK(border == expected);
  }
}
