// Differential test: zero-displacement dbss subdivision, as the spec's
// reference decoder (spec/reference) evaluates it, against OpenMesh's
// Modified Butterfly subdivider, an independent implementation, on closed
// meshes with valences 3 to 12.
#include <catch2/catch.hpp>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>

#include <cmath>

#include "../shapes.h"
#include "dbss/decoder/topology.h"
#include "reference.h"

namespace {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

void check_against_openmesh(const dbss::TriangleMesh& base, const char* name, int levels) {
  INFO(name);
  OMesh om;
  std::vector<OMesh::VertexHandle> handles;
  for (size_t v = 0; v < base.vertex_count(); ++v)
    handles.push_back(om.add_vertex(OMesh::Point(base.positions[3 * v], base.positions[3 * v + 1], base.positions[3 * v + 2])));
  for (size_t f = 0; f < base.triangle_count(); ++f)
    om.add_face(handles[base.triangles[3 * f]], handles[base.triangles[3 * f + 1]], handles[base.triangles[3 * f + 2]]);
  REQUIRE(om.n_faces() == base.triangle_count());

  double diag2 = 0;
  for (int a = 0; a < 3; ++a) {
    float lo = 1e30f, hi = -1e30f;
    for (size_t v = 0; v < base.vertex_count(); ++v) lo = std::min(lo, base.positions[3 * v + a]), hi = std::max(hi, base.positions[3 * v + a]);
    diag2 += double(hi - lo) * (hi - lo);
  }
  const double tol = 1e-5 * std::sqrt(diag2);

  auto topo = dbss::build_topology(static_cast<uint32_t>(base.vertex_count()), base.triangles);
  REQUIRE(topo.ok());
  dbss::LevelTopology t = std::move(topo).value();
  std::vector<float> pos = base.positions;
  // ours[v] = OpenMesh vertex index of our vertex v.
  std::vector<int> ours(base.vertex_count());
  for (size_t v = 0; v < ours.size(); ++v) ours[v] = static_cast<int>(v);

  for (int level = 1; level <= levels; ++level) {
    INFO("level " << level);
    const size_t old_count = om.n_vertices();
    OpenMesh::Subdivider::Uniform::ModifiedButterflyT<OMesh> sub;
    sub.attach(om);
    REQUIRE(sub(1));
    sub.detach();

    std::vector<float> next = dbss_ref::subdivide(dbss_ref::Mesh{pos, t.triangles, {}, {}}, {}, 0.0f).positions;
    // Map each odd vertex (edge a-b) to OpenMesh's new vertex next to both.
    std::vector<int> next_map(t.vertex_count + t.edge_count());
    for (uint32_t v = 0; v < t.vertex_count; ++v) next_map[v] = ours[v];
    double worst = 0;
    for (uint32_t e = 0; e < t.edge_count(); ++e) {
      const uint32_t h = t.edge_half[e];
      const auto a = om.vertex_handle(ours[t.triangles[h]]);
      const auto b = om.vertex_handle(ours[t.triangles[dbss::next_half(h)]]);
      int found = -1;
      for (auto x : om.vv_range(a))
        if (static_cast<size_t>(x.idx()) >= old_count)
          for (auto y : om.vv_range(x))
            if (y == b) found = x.idx();
      REQUIRE(found >= 0);
      next_map[t.vertex_count + e] = found;
      const auto p = om.point(om.vertex_handle(found));
      const float* q = &next[3 * (size_t{t.vertex_count} + e)];
      worst = std::max({worst, std::abs(q[0] - double(p[0])), std::abs(q[1] - double(p[1])), std::abs(q[2] - double(p[2]))});
    }
    CHECK(worst <= tol);
    ours = std::move(next_map);
    pos = std::move(next);
    t = dbss::refine_topology(t);
  }
}

}  // namespace

TEST_CASE("zero-displacement subdivision matches OpenMesh's Modified Butterfly on closed meshes") {
  check_against_openmesh(dbss::test::jitter(dbss::test::tetrahedron(), 0.2f), "tetrahedron (valence 3)", 4);
  check_against_openmesh(dbss::test::jitter(dbss::test::bipyramid(4), 0.1f), "octahedron (valence 4)", 4);
  check_against_openmesh(dbss::test::jitter(dbss::test::icosahedron(), 0.2f), "icosahedron (valence 5)", 4);
  check_against_openmesh(dbss::test::jitter(dbss::test::torus(8, 6), 0.05f), "torus (valence 6)", 4);
  for (uint32_t n = 7; n <= 12; ++n)
    check_against_openmesh(dbss::test::jitter(dbss::test::bipyramid(n), 0.1f, n), "bipyramid (valence n and 4)", 4);
  check_against_openmesh(dbss::test::jitter(dbss::test::uv_sphere(5, 9), 0.05f), "uv sphere (valence 9 poles)", 4);
}

TEST_CASE("zero-displacement subdivision matches OpenMesh's Modified Butterfly on bordered meshes") {
  // Boundary edges (4-point rule) and interior edges touching the border
  // (reflected wings), on a grid with valences 2 to 8 along its border.
  check_against_openmesh(dbss::test::jitter(dbss::test::planar_grid(5, 4), 0.1f), "jittered grid", 3);
}
