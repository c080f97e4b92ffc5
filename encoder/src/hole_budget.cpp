// The control budget per hole.  It replaces a floor of 14 faces per
// boundary loop (tuned on elephant-with-holes alone), which gave a
// six-edge hole and a winding 78-edge one the same share: a hole now gets
// the rim vertices its curve needs at a tolerance tied to the closed
// budget's edge length, and the faces those take plus a ring of interior
// faces as fine as its rim.  Measured in bench/lod_bench.md, "Issue 18,
// fifth session".
#include "dbss/encoder/hole_budget.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "dbss/encoder/open_surface.h"
#include "dbss/encoder/simplify.h"
#include "mesh_geometry.h"

namespace dbss {

namespace {

double dist2(const float* a, const float* b) {
  double s = 0;
  for (int k = 0; k < 3; ++k) s += (double{a[k]} - b[k]) * (double{a[k]} - b[k]);
  return s;
}

}  // namespace

uint32_t loop_vertices_needed(const std::vector<float>& positions, const std::vector<uint32_t>& loop, double tolerance) {
  const size_t n = loop.size();
  if (n <= 3) return 3;
  const auto at = [&](size_t i) { return &positions[3 * size_t{loop[i % n]}]; };
  const auto point = [&](size_t i) {
    const float* p = at(i);
    return mesh_geometry::V3{p[0], p[1], p[2]};
  };
  // Two mutually far vertices split the loop into two chains.
  size_t a = 0, b = 0;
  for (int pass = 0; pass < 2; ++pass) {
    size_t far = a;
    double best = -1;
    for (size_t i = 0; i < n; ++i)
      if (const double d = dist2(at(a), at(i)); d > best) best = d, far = i;
    if (pass == 0) a = far;
    else b = far;
  }
  if (a == b) return 3;
  if (a > b) std::swap(a, b);
  const double tol2 = tolerance * tolerance;
  uint32_t kept = 2;
  // Chains as index ranges [i, j] along the loop (j may pass n: wrapped).
  std::vector<std::pair<size_t, size_t>> todo = {{a, b}, {b, a + n}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    size_t worst = i;
    double worst_d = tol2;
    for (size_t k = i + 1; k < j; ++k)
      if (const double d = mesh_geometry::distance2_to_segment(point(k), point(i), point(j)); d > worst_d) worst_d = d, worst = k;
    if (worst == i) continue;
    ++kept;
    todo.push_back({i, worst});
    todo.push_back({worst, j});
  }
  return std::max<uint32_t>(kept, 3);
}

HoleBudget hole_budget(const TriangleMesh& m, int64_t genus, double tolerance, double faces_per_vertex) {
  HoleBudget r;
  r.closed_faces = default_control_faces(static_cast<uint32_t>(m.triangle_count()), genus);
  r.faces = r.closed_faces;
  const std::vector<std::vector<uint32_t>> loops = boundary_loops(m);
  if (loops.empty()) return r;
  const double area = mesh_area(m);
  // An equilateral triangle of area / closed_faces: side^2 * sqrt(3) / 4.
  r.edge_length = std::sqrt(4 * area / (std::sqrt(3.0) * std::max<uint32_t>(1, r.closed_faces)));
  double extra = 0;
  for (const auto& loop : loops) {
    const uint32_t n = loop_vertices_needed(m.positions, loop, tolerance * r.edge_length);
    r.loop_vertices.push_back(n);
    extra += faces_per_vertex * n + 2;
  }
  // At most three quarters of the input's triangles (never under the closed
  // budget): a raw scan with thousands of tiny holes would otherwise ask for
  // more faces than it has, QEM would do nothing and every level would
  // grow 4x from the input itself.
  const double cap = std::max(static_cast<double>(r.closed_faces), 0.75 * static_cast<double>(m.triangle_count()));
  const double total = std::min({static_cast<double>(r.closed_faces) + extra, cap, UINT32_MAX - 1.0});
  r.faces = static_cast<uint32_t>(total) & ~1u;
  return r;
}

}  // namespace dbss
