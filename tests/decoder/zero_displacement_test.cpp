// The decoder copies an odd vertex whose q is 0 instead of computing its
// normal (zero_displacement.h).  That is the same bits only where every
// point is finite and the stencil point has no -0 coordinate; these tests
// build exactly the other cases (a -0 that section 7 turns into +0, an
// infinite point whose normal is NaN) and check every kernel build against
// the spec's reference evaluation, level by level, bit for bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "../shapes.h"
#include "dbss/decoder/topology.h"
#include "reference.h"
#include "refinement_step.h"

using namespace dbss;

namespace {

uint32_t bits_of(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

// Equal bits, or both NaN (a NaN's sign and payload are the processor's).
bool same_floats(std::span<const float> a, const std::vector<float>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!(bits_of(a[i]) == bits_of(b[i]) || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  return true;
}

// Two levels of `m` by the decoder's Refiner with `q_at(level, edge)`, each
// against the reference's step from the same level.
template <class QAt>
void check_levels(const TriangleMesh& m, QAt q_at, Kernels kernels) {
  auto topo = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
  REQUIRE(topo.ok());
  detail::Refiner r(kernels);
  r.reset(topo.value(), m.positions);
  dbss_ref::Mesh ref{m.positions, m.triangles, {}, {}};
  for (int level = 1; level <= 2; ++level) {
    std::vector<int32_t> q(static_cast<size_t>(r.counts().edges));
    for (size_t e = 0; e < q.size(); ++e) q[e] = q_at(level, e);
    r.step(q, 0.25f, 1);
    ref = dbss_ref::subdivide(ref, q, 0.25f);
    INFO("level " << level << ", kernels " << static_cast<int>(kernels));
    REQUIRE(same_floats(r.positions(), ref.positions));
  }
}

// A torus whose z coordinates are tiny subnormal multiples (-2..2) of the
// smallest float: the stencil sums come out as tiny negative values that
// round to -0, and a zero displacement along a normal with positive z
// turns those into +0.
TriangleMesh subnormal_torus() {
  TriangleMesh m = test::jitter(test::torus(12, 9), 0.05f);
  const float tiny = std::numeric_limits<float>::denorm_min();
  for (size_t v = 0; v < m.vertex_count(); ++v) m.positions[3 * v + 2] = static_cast<float>(int(v % 5) - 2) * tiny;
  return m;
}

constexpr Kernels kAll[] = {Kernels::best, Kernels::baseline, Kernels::scalar, Kernels::paired};

}  // namespace

TEST_CASE("zero displacements: the test mesh has -0 stencil points that section 7 turns into +0") {
  // Without this the next test would not test the -0 case.
  const TriangleMesh m = subnormal_torus();
  const dbss_ref::Mesh plain = dbss_ref::subdivide(dbss_ref::Mesh{m.positions, m.triangles, {}, {}}, {}, 0.0f);
  auto topo = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
  REQUIRE(topo.ok());
  const std::vector<int32_t> zeros(topo.value().edge_count(), 0);
  const dbss_ref::Mesh moved = dbss_ref::subdivide(dbss_ref::Mesh{m.positions, m.triangles, {}, {}}, zeros, 0.25f);
  size_t negative_zero = 0, turned = 0;
  for (size_t i = 3 * m.vertex_count(); i < plain.positions.size(); ++i) {
    if (bits_of(plain.positions[i]) != 0x80000000u) continue;
    ++negative_zero;
    turned += bits_of(moved.positions[i]) == 0;
  }
  CHECK(negative_zero > 10);
  CHECK(turned > 0);
}

TEST_CASE("zero displacements give the reference's bits: all-zero and mixed levels, -0 and infinite points") {
  for (Kernels k : kAll) {
    // An ordinary mesh: all zeros, then every third edge non-zero.
    const TriangleMesh smooth = test::jitter(test::torus(16, 10), 0.05f);
    check_levels(smooth, [](int, size_t) { return 0; }, k);
    check_levels(smooth, [](int, size_t e) { return e % 3 ? 0 : static_cast<int32_t>(e % 7) - 3; }, k);
    // Stencil points with -0 coordinates.
    const TriangleMesh tiny = subnormal_torus();
    check_levels(tiny, [](int, size_t) { return 0; }, k);
    check_levels(tiny, [](int, size_t e) { return e % 2 ? 0 : 1; }, k);
    // An infinite point: NaN normals around it, and a zero displacement
    // along a NaN normal is NaN, not the stencil point.
    TriangleMesh inf = smooth;
    inf.positions[3 * 17] = std::numeric_limits<float>::infinity();
    check_levels(inf, [](int, size_t) { return 0; }, k);
    check_levels(inf, [](int, size_t e) { return e % 2 ? 0 : -2; }, k);
  }
}
