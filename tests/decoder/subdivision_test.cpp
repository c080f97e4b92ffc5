#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <set>

#include "../shapes.h"
#include "butterfly.h"
#include "dbss/decoder/level_refiner.h"
#include "dbss/decoder/topology.h"
#include "dbss/format/container.h"
#include "reference.h"

using namespace dbss;

namespace {

LevelTopology topology_of(const TriangleMesh& m) {
  auto t = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
  REQUIRE(t.ok());
  return std::move(t).value();
}

// Subdivides `levels` times with pseudo-random displacements (or none),
// evaluated by the spec's reference decoder (spec/reference); the topology
// of every level is the decoder's refine_topology().
struct Chain {
  std::vector<std::vector<float>> positions;
  std::vector<LevelTopology> topology;
};

Chain subdivide(const TriangleMesh& m, int levels, int32_t amplitude = 0) {
  Chain c;
  c.topology.push_back(topology_of(m));
  c.positions.push_back(m.positions);
  dbss_ref::Mesh mesh{m.positions, m.triangles, {}, {}};
  uint32_t s = 12345;
  for (int l = 0; l < levels; ++l) {
    std::vector<int32_t> q;
    if (amplitude) {
      q.resize(c.topology.back().edge_count());
      for (auto& v : q) {
        s = s * 1664525u + 1013904223u;
        v = static_cast<int32_t>((s >> 8) % (2 * uint32_t(amplitude) + 1)) - amplitude;
      }
    }
    mesh = dbss_ref::subdivide(mesh, q, 1e-3f);
    c.positions.push_back(mesh.positions);
    c.topology.push_back(refine_topology(c.topology.back()));
    REQUIRE(mesh.triangles == c.topology.back().triangles);
  }
  return c;
}

// The reference's plain subdivision of one level.
std::vector<float> plain_step(const TriangleMesh& m) {
  return dbss_ref::subdivide(dbss_ref::Mesh{m.positions, m.triangles, {}, {}}, {}, 0.0f).positions;
}

}  // namespace

TEST_CASE("extraordinary weights: 3/4 plus the s_j sum to 1, symmetric, valences 3..20") {
  for (uint32_t k = 3; k <= 20; ++k) {
    double sum = 0.75;
    for (uint32_t j = 0; j < k; ++j) {
      sum += butterfly_weight(k, j);
      if (j > 0) CHECK(butterfly_weight(k, j) == butterfly_weight(k, k - j));
    }
    INFO("valence " << k);
    CHECK(std::abs(sum - 1.0) < 1e-15);
  }
  CHECK(butterfly_weight(3, 0) == 5.0 / 12);
  CHECK(butterfly_weight(4, 2) == -1.0 / 8);
  CHECK(butterfly_weight(4, 1) == 0.0);
  // Stencils as built: every row sums to 1 (affine invariance).
  for (const TriangleMesh& m : {test::icosahedron(), test::bipyramid(11), test::planar_grid(5, 4), test::torus(6, 5)}) {
    const Stencils s = build_stencils(topology_of(m));
    std::vector<uint32_t> index;
    std::vector<double> weight;
    for (uint32_t e = 0; e < s.size(); ++e) {
      stencil_terms(s, e, index, weight);
      REQUIRE(!index.empty());
      double sum = 0;
      for (double w : weight) sum += w;
      REQUIRE(std::abs(sum - 1.0) < 1e-14);
    }
  }
}

TEST_CASE("Table 1 counts: genus 1 with 50 vertices and genus 0 with 107") {
  auto check = [](const TriangleMesh& m, std::array<uint64_t, 3> odd, std::array<uint64_t, 3> total) {
    LevelTopology t = topology_of(m);
    for (int l = 0; l < 3; ++l) {
      CHECK(t.edge_count() == odd[l]);
      t = refine_topology(t);
      CHECK(t.vertex_count == total[l]);
      CHECK(t.triangle_count() == m.triangle_count() << (2 * (l + 1)));
      // The format's count recurrence agrees with the refined topology.
      const auto counts = format::counts_at_level({m.vertex_count(), topology_of(m).edge_count(), m.triangle_count()}, l + 1);
      CHECK(counts->vertices == t.vertex_count);
      CHECK(counts->edges == t.edge_count());
      CHECK(counts->triangles == t.triangle_count());
    }
  };
  check(test::torus(10, 5), {150, 600, 2400}, {200, 800, 3200});
  check(test::uv_sphere(7, 15), {315, 1260, 5040}, {422, 1682, 6722});
}

TEST_CASE("refined topology equals a topology built from scratch from the refined triangles") {
  for (const TriangleMesh& m : {test::icosahedron(), test::planar_grid(4, 3), test::torus(5, 4), test::bipyramid(9)}) {
    LevelTopology t = topology_of(m);
    for (int l = 0; l < 3; ++l) {
      const LevelTopology fast = refine_topology(t);
      auto slow = build_topology(fast.vertex_count, fast.triangles);
      REQUIRE(slow.ok());
      CHECK(fast.twin == slow.value().twin);
      CHECK(fast.edge_of == slow.value().edge_of);
      CHECK(fast.edge_half == slow.value().edge_half);
      CHECK(fast.vertex_valence == slow.value().vertex_valence);
      CHECK(fast.vertex_boundary == slow.value().vertex_boundary);
      // Starts may differ on closed fans (any outgoing half-edge walks the whole
      // fan); on the boundary they must be the outgoing boundary half-edge.
      for (uint32_t v = 0; v < fast.vertex_count; ++v) {
        CHECK(fast.triangles[fast.vertex_start[v]] == v);
        if (fast.vertex_boundary[v]) CHECK(fast.vertex_start[v] == slow.value().vertex_start[v]);
      }
      t = fast;
    }
  }
}

TEST_CASE("even vertices never move, at every level, with displacements") {
  const Chain c = subdivide(test::jitter(test::icosahedron(), 0.2f), 4, 50);
  for (size_t l = 1; l < c.positions.size(); ++l) {
    const auto& prev = c.positions[l - 1];
    REQUIRE(std::equal(prev.begin(), prev.end(), c.positions[l].begin()));
  }
}

TEST_CASE("a planar mesh stays planar, boundary and irregular valences included") {
  const Chain c = subdivide(test::planar_grid(6, 5), 4);
  for (size_t i = 2; i < c.positions.back().size(); i += 3) REQUIRE(c.positions.back()[i] == 0.0f);
  // A tilted plane: distance to it stays at rounding level.
  TriangleMesh tilted = test::planar_grid(6, 5);
  for (size_t i = 0; i < tilted.positions.size(); i += 3) {
    const float x = tilted.positions[i], y = tilted.positions[i + 1];
    tilted.positions[i + 2] = 0.3f * x - 0.7f * y + 2.0f;
  }
  const Chain t = subdivide(tilted, 4);
  for (size_t i = 0; i < t.positions.back().size(); i += 3) {
    const auto& p = t.positions.back();
    REQUIRE(std::abs(p[i + 2] - (0.3 * p[i] - 0.7 * p[i + 1] + 2.0)) < 1e-5);
  }
}

TEST_CASE("the regular 8-point stencil on a hand-built patch gives the hand-computed point") {
  // A regular lattice: quad (i, j) split along its (i,j)-(i+1,j+1) diagonal,
  // so every interior vertex has valence 6.
  const uint32_t n = 6;
  TriangleMesh m;
  auto id = [&](uint32_t i, uint32_t j) { return j * (n + 1) + i; };
  auto height = [](uint32_t i, uint32_t j) { return static_cast<float>((i * 7 + j * 13) % 5) * 0.25f - 0.3f * i; };
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n; ++i) m.positions.insert(m.positions.end(), {float(i), float(j), height(i, j)});
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const LevelTopology t = topology_of(m);
  // Edge u = (2,2), w = (3,2): opposite vertices (2,1) and (3,3); wings
  // (3,1), (1,1), (2,3), (4,3).
  const uint32_t u = id(2, 2), w = id(3, 2);
  uint32_t edge = kNoHalfEdge;
  for (uint32_t h = 0; h < t.triangles.size(); ++h)
    if (t.triangles[h] == u && t.triangles[next_half(h)] == w) edge = t.edge_of[h];
  REQUIRE(edge != kNoHalfEdge);
  auto z = [&](uint32_t i, uint32_t j) { return double(height(i, j)); };
  const double expect = 0.5 * (z(2, 2) + z(3, 2)) + 0.125 * (z(2, 1) + z(3, 3)) -
                        0.0625 * (z(3, 1) + z(1, 1) + z(2, 3) + z(4, 3));
  const std::vector<float> out = plain_step(m);
  const float* p = &out[3 * (size_t{t.vertex_count} + edge)];
  CHECK(p[0] == 2.5f);
  CHECK(p[1] == 2.0f);
  CHECK(p[2] == Approx(expect).margin(1e-6));
}

TEST_CASE("bordered meshes are crack-free: two halves sharing a border subdivide to the same border") {
  // Cut a sphere along its equator ring into two bordered caps.
  const TriangleMesh sphere = test::jitter(test::uv_sphere(7, 12), 0.03f);
  TriangleMesh caps[2];
  for (int c = 0; c < 2; ++c) caps[c].positions = sphere.positions;
  for (size_t f = 0; f < sphere.triangle_count(); ++f) {
    double z = 0;
    for (int k = 0; k < 3; ++k) z += sphere.positions[3 * sphere.triangles[3 * f + k] + 2];
    auto& cap = caps[z > 0 ? 0 : 1];
    cap.triangles.insert(cap.triangles.end(), &sphere.triangles[3 * f], &sphere.triangles[3 * f + 3]);
  }
  // Drop unused vertices so each cap is a valid mesh.
  std::set<std::array<float, 3>> borders[2];
  for (int c = 0; c < 2; ++c) {
    TriangleMesh compact;
    std::vector<uint32_t> remap(sphere.vertex_count(), kNoHalfEdge);
    for (uint32_t& v : caps[c].triangles) {
      if (remap[v] == kNoHalfEdge) {
        remap[v] = static_cast<uint32_t>(compact.vertex_count());
        compact.positions.insert(compact.positions.end(), &sphere.positions[3 * v], &sphere.positions[3 * v + 3]);
      }
      compact.triangles.push_back(remap[v]);
    }
    const Chain ch = subdivide(compact, 3);
    const LevelTopology& t = ch.topology.back();
    for (uint32_t v = 0; v < t.vertex_count; ++v)
      if (t.vertex_boundary[v]) borders[c].insert({ch.positions.back()[3 * v], ch.positions.back()[3 * v + 1], ch.positions.back()[3 * v + 2]});
  }
  CHECK(borders[0].size() == 12 * 8);
  CHECK(borders[0] == borders[1]);
}

TEST_CASE("non-manifold and inconsistent input is rejected with bad_mesh") {
  // Three triangles on one edge.
  std::vector<uint32_t> fin = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  CHECK(build_topology(5, fin).status().code() == ErrorCode::bad_mesh);
  // Two fans through vertex 0 (a bow tie).
  std::vector<uint32_t> bowtie = {0, 1, 2, 0, 3, 4};
  auto r = build_topology(5, bowtie);
  CHECK(r.status().code() == ErrorCode::bad_mesh);
  CHECK(r.status().message().find("vertex 0") != std::string::npos);
  // Inconsistent orientation.
  std::vector<uint32_t> flipped = {0, 1, 2, 0, 1, 3};
  CHECK(build_topology(4, flipped).status().code() == ErrorCode::bad_mesh);
  // Out of range, degenerate, unused vertex.
  CHECK(build_topology(3, std::vector<uint32_t>{0, 1, 3}).status().code() == ErrorCode::bad_mesh);
  CHECK(build_topology(3, std::vector<uint32_t>{0, 1, 1}).status().code() == ErrorCode::bad_mesh);
  CHECK(build_topology(4, std::vector<uint32_t>{0, 1, 2}).status().code() == ErrorCode::bad_mesh);
  CHECK(build_topology(3, std::vector<uint32_t>{0, 1, 2}).ok());
}

TEST_CASE("the thread count does not change a single bit") {
  // The fast path (LevelRefiner runs the decoder's kernels) on 1 to 3
  // threads, four levels deep, against the single-threaded reference.
  const TriangleMesh m = test::jitter(test::uv_sphere(20, 40), 0.01f);
  const Chain ref = subdivide(m, 4, 30);
  for (unsigned threads : {1u, 2u, 3u}) {
    auto r = LevelRefiner::create(m);
    REQUIRE(r.ok());
    uint32_t s = 12345;  // the same q sequence as subdivide()
    std::vector<int32_t> q;
    for (int l = 0; l < 4; ++l) {
      // Odd vertices are chosen concurrently, so take their q from a table.
      std::vector<int32_t> table(r.value().next_odd_count());
      for (auto& v : table) {
        s = s * 1664525u + 1013904223u;
        v = static_cast<int32_t>((s >> 8) % 61u) - 30;
      }
      r.value().refine([&](uint32_t e, const double*, const double*, const float*, const float*) { return table[e]; },
                       1e-3f, q, threads);
    }
    INFO(threads << " threads");
    REQUIRE(ref.positions.back().size() > 6 * 32768);
    REQUIRE(r.value().positions().size() == ref.positions.back().size());
    CHECK(std::memcmp(r.value().positions().data(), ref.positions.back().data(), 4 * ref.positions.back().size()) == 0);
  }
}

TEST_CASE("displacement moves odd vertices along the unit normal by q * step") {
  // A flat grid: every normal is +z or -z, so a displaced odd vertex moves
  // only in z, by exactly q * step.
  const TriangleMesh m = test::planar_grid(5, 5);
  const LevelTopology t = topology_of(m);
  std::vector<int32_t> q(t.edge_count());
  for (size_t i = 0; i < q.size(); ++i) q[i] = static_cast<int32_t>(i % 7) - 3;
  const std::vector<float> flat = plain_step(m);
  const std::vector<float> moved = dbss_ref::subdivide(dbss_ref::Mesh{m.positions, m.triangles, {}, {}}, q, 0.5f).positions;
  for (size_t i = 0; i < q.size(); ++i) {
    const float* a = &flat[3 * (t.vertex_count + i)];
    const float* b = &moved[3 * (t.vertex_count + i)];
    CHECK(a[0] == b[0]);
    CHECK(a[1] == b[1]);
    CHECK(std::abs(b[2] - a[2]) == Approx(0.5 * std::abs(q[i])));
    if (q[i]) CHECK((b[2] - a[2] > 0) == (q[i] > 0));  // counter-clockwise triangles face +z
  }
}

TEST_CASE("the regular fast path gives the same bits as the generic weighted lists") {
  for (const TriangleMesh& m : {test::jitter(test::torus(9, 7), 0.05f), test::jitter(test::uv_sphere(6, 10), 0.05f),
                                test::jitter(test::planar_grid(6, 5), 0.1f)}) {
    LevelTopology t = topology_of(m);
    t = refine_topology(t);  // mostly regular edges
    const std::vector<float> pos = plain_step(m);
    const Stencils fast = build_stencils(t), slow = build_stencils(t, /*all_generic=*/true);
    REQUIRE(!fast.regular_odd.empty());
    REQUIRE(slow.regular_odd.empty());
    auto evaluate = [&](const Stencils& st) {
      std::vector<float> odd(3 * size_t{st.size()});
      apply_stencils(st, pos.data(), 0, static_cast<uint32_t>(st.regular_odd.size()), 0,
                     static_cast<uint32_t>(st.other_odd.size()), odd.data());
      return odd;
    };
    const std::vector<float> a = evaluate(fast), b = evaluate(slow);
    CHECK(a == b);
    // And both are the reference's odd vertices of the next level.
    const std::vector<float> ref = plain_step(TriangleMesh{pos, t.triangles});
    CHECK(std::equal(a.begin(), a.end(), ref.begin() + 3 * size_t{t.vertex_count}, ref.end()));
  }
}

TEST_CASE("all-zero displacements give exactly plain butterfly subdivision") {
  // The fast path (LevelRefiner) choosing q = 0 everywhere against the
  // reference's plain subdivision, three levels deep.
  for (const dbss::TriangleMesh& m : {dbss::test::jitter(dbss::test::torus(9, 7), 0.05f),
                                      dbss::test::jitter(dbss::test::bipyramid(11), 0.1f),
                                      dbss::test::jitter(dbss::test::planar_grid(6, 5), 0.1f)}) {
    auto r = dbss::LevelRefiner::create(m);
    REQUIRE(r.ok());
    dbss_ref::Mesh plain{m.positions, m.triangles, {}, {}};
    std::vector<int32_t> q;
    for (int level = 1; level <= 3; ++level) {
      plain = dbss_ref::subdivide(plain, {}, 0.0f);
      r.value().refine([](uint32_t, const double*, const double*, const float*, const float*) { return 0; }, 0.37f,
                       q, 1);
      const auto zero = r.value().positions();
      REQUIRE(plain.positions.size() == zero.size());
      // Equal values (a zero displacement may turn -0 into +0, nothing else).
      for (size_t i = 0; i < zero.size(); ++i) REQUIRE(plain.positions[i] == zero[i]);
    }
  }
}

TEST_CASE("LevelRefiner (the encoder's closed loop) places vertices as the reference evaluation does, any thread count") {
  for (const dbss::TriangleMesh& m : {dbss::test::jitter(dbss::test::torus(40, 30), 0.02f),
                                      dbss::test::jitter(dbss::test::planar_grid(30, 20), 0.1f)}) {
    auto t = dbss::build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
    REQUIRE(t.ok());
    for (unsigned threads : {1u, 2u, 3u}) {
      auto r = dbss::LevelRefiner::create(m);
      REQUIRE(r.ok());
      dbss::LevelTopology topo = t.value();
      dbss_ref::Mesh ref{m.positions, m.triangles, {}, {}};
      for (int level = 1; level <= 3; ++level) {
        // The chooser sees the reference's undisplaced point and its edge's
        // ends, and picks a q that depends on them.
        const dbss_ref::Mesh plain = dbss_ref::subdivide(ref, {}, 0.0f);
        const size_t evens = ref.positions.size() / 3;
        std::vector<int32_t> q;
        std::atomic<bool> points_agree{true}, ends_agree{true};  // written from the step's threads
        const dbss::OddChooser choose = [&](uint32_t e, const double p[3], const double n[3], const float* a,
                                            const float* b) {
          const float* want = &plain.positions[3 * (evens + e)];
          if (!(p[0] == want[0] && p[1] == want[1] && p[2] == want[2])) points_agree = false;
          const uint32_t h = topo.edge_half[e];
          if (a != r.value().positions().data() + 3 * size_t{topo.triangles[h]} ||
              b != r.value().positions().data() + 3 * size_t{topo.triangles[dbss::next_half(h)]})
            ends_agree = false;
          (void)n;
          return static_cast<int32_t>(e % 7) - 3;
        };
        r.value().refine(choose, 0.01f, q, threads);
        CHECK(points_agree.load());
        CHECK(ends_agree.load());
        const dbss_ref::Mesh next = dbss_ref::subdivide(ref, q, 0.01f);
        REQUIRE(r.value().positions().size() == next.positions.size());
        CHECK(std::memcmp(r.value().positions().data(), next.positions.data(), next.positions.size() * 4) == 0);
        topo = dbss::refine_topology(topo);
        CHECK(std::equal(topo.triangles.begin(), topo.triangles.end(), r.value().triangles().begin()));
        CHECK(next.triangles == topo.triangles);
        ref = next;
      }
    }
  }
}
