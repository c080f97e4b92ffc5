// Mesh input: checking the input is a manifold, the control mesh simplified
// from it, and displacements cast against its triangles.
#include "dbss/encoder/mesh_input.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "dbss/decoder/topology.h"
#include "dbss/encoder/simplify.h"

namespace dbss {

namespace {

std::string edge_name(uint32_t a, uint32_t b) {
  return "edge " + std::to_string(std::min(a, b)) + "-" + std::to_string(std::max(a, b));
}

// The manifold checks of build_topology without its valence limit (an
// input may have a pole of any valence; only the control mesh must keep
// under the format's), in the input's vertex numbering `names`.
Status check_manifold(uint32_t vertex_count, const std::vector<uint32_t>& tri, const std::vector<uint32_t>& names) {
  const uint32_t halves = static_cast<uint32_t>(tri.size());
  const auto nxt = [](uint32_t h) { return next_half(h); };
  std::vector<uint64_t> keys(halves);
  for (uint32_t h = 0; h < halves; ++h) {
    const uint64_t a = tri[h], b = tri[nxt(h)];
    keys[h] = std::min(a, b) << 32 | std::max(a, b);
  }
  std::vector<uint32_t> order(halves);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return keys[x] < keys[y] || (keys[x] == keys[y] && x < y); });
  std::vector<uint32_t> twin(halves, kNoHalfEdge);
  // The first offending edge in the input's numbering: the smallest pair.
  Status first;
  uint64_t first_key = ~uint64_t{0};
  auto offend = [&](uint32_t a, uint32_t b, const std::string& what) {
    const uint64_t k = uint64_t{std::min(names[a], names[b])} << 32 | std::max(names[a], names[b]);
    if (k < first_key) first_key = k, first = Status(ErrorCode::invalid_argument, edge_name(names[a], names[b]) + what);
  };
  for (uint32_t i = 0; i < halves;) {
    uint32_t j = i + 1;
    while (j < halves && keys[order[j]] == keys[order[i]]) ++j;
    const uint32_t a = tri[order[i]], b = tri[nxt(order[i])];
    if (j - i > 2) {
      offend(a, b, " is shared by " + std::to_string(j - i) + " triangles (non-manifold)");
    } else if (j - i == 2) {
      const uint32_t x = order[i], y = order[i + 1];
      if (tri[x] == tri[y]) offend(a, b, " is used twice in the same direction (inconsistent orientation)");
      else twin[x] = y, twin[y] = x;
    }
    i = j;
  }
  if (!first.ok()) return first;
  // Fans: a vertex's triangles, walked across twins, must all be reached
  // from one start.
  std::vector<uint32_t> corners(vertex_count, 0), any_out(vertex_count, kNoHalfEdge);
  for (uint32_t h = 0; h < halves; ++h) ++corners[tri[h]], any_out[tri[h]] = h;
  uint32_t worst = kNoHalfEdge;
  for (uint32_t v = 0; v < vertex_count; ++v) {
    uint32_t start = any_out[v];
    for (uint32_t steps = 0; steps < corners[v]; ++steps) {
      const uint32_t o = twin[start];
      if (o == kNoHalfEdge) break;
      start = nxt(o);
      if (start == any_out[v]) break;
    }
    uint32_t fan = 0, h = start;
    do {
      ++fan;
      const uint32_t o = twin[prev_half(h)];
      if (o == kNoHalfEdge) break;
      h = o;
    } while (h != start && fan <= corners[v]);
    if (fan != corners[v] && (worst == kNoHalfEdge || names[v] < names[worst])) worst = v;
  }
  if (worst != kNoHalfEdge)
    return Status(ErrorCode::invalid_argument, "vertex " + std::to_string(names[worst]) + " joins " +
                                                   std::to_string(corners[worst]) +
                                                   " triangles in more than one fan (a bow-tie: non-manifold)");
  return {};
}

inline double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

Result<TriangleMesh> prepare_mesh_input(const TriangleMesh& in, MeshCleanup* cleanup) {
  const size_t nv = in.vertex_count();
  if (in.triangles.empty() || in.triangles.size() % 3 != 0)
    return Status(ErrorCode::invalid_argument, "the mesh has no triangles");
  MeshCleanup c;
  std::vector<uint32_t> kept;
  kept.reserve(in.triangles.size());
  for (size_t f = 0; f < in.triangle_count(); ++f) {
    const uint32_t a = in.triangles[3 * f], b = in.triangles[3 * f + 1], d = in.triangles[3 * f + 2];
    if (a >= nv || b >= nv || d >= nv)
      return Status(ErrorCode::invalid_argument, "triangle " + std::to_string(f) + " names a vertex past " + std::to_string(nv));
    if (a == b || b == d || d == a) {
      ++c.degenerate_triangles;
      continue;
    }
    kept.insert(kept.end(), {a, b, d});
  }
  if (kept.empty()) return Status(ErrorCode::invalid_argument, "every triangle of the mesh repeats a vertex");
  std::vector<uint32_t> remap(nv, kNoHalfEdge), names;
  TriangleMesh out;
  for (uint32_t& v : kept) {
    if (remap[v] == kNoHalfEdge) {
      remap[v] = static_cast<uint32_t>(names.size());
      names.push_back(v);
    }
    v = remap[v];
  }
  // Vertices in their input order (first use would shuffle them).
  std::vector<uint32_t> by_input(names.size());
  std::iota(by_input.begin(), by_input.end(), 0u);
  std::sort(by_input.begin(), by_input.end(), [&](uint32_t x, uint32_t y) { return names[x] < names[y]; });
  std::vector<uint32_t> final_index(names.size());
  for (uint32_t i = 0; i < by_input.size(); ++i) final_index[by_input[i]] = i;
  for (uint32_t& v : kept) v = final_index[v];
  std::vector<uint32_t> sorted_names(names.size());
  out.positions.resize(3 * names.size());
  for (uint32_t i = 0; i < by_input.size(); ++i) {
    sorted_names[i] = names[by_input[i]];
    for (int a = 0; a < 3; ++a) out.positions[3 * i + a] = in.positions[3 * size_t{sorted_names[i]} + a];
  }
  c.unused_vertices = nv - names.size();
  out.triangles = std::move(kept);
  if (Status s = check_manifold(static_cast<uint32_t>(out.vertex_count()), out.triangles, sorted_names); !s.ok()) return s;
  if (cleanup) *cleanup = c;
  return out;
}

namespace {
TriangleMesh rim_of(const TriangleMesh& m) {
  // Boundary edges: half-edges with no opposite.
  std::vector<uint64_t> keys;
  keys.reserve(m.triangles.size());
  for (uint32_t h = 0; h < m.triangles.size(); ++h) keys.push_back(uint64_t{m.triangles[h]} << 32 | m.triangles[next_half(h)]);
  std::vector<uint64_t> sorted = keys;
  std::sort(sorted.begin(), sorted.end());
  TriangleMesh rim;
  rim.positions = m.positions;
  for (uint64_t k : keys) {
    const uint64_t reverse = (k & 0xFFFFFFFFu) << 32 | (k >> 32);
    if (std::binary_search(sorted.begin(), sorted.end(), reverse)) continue;
    const uint32_t a = static_cast<uint32_t>(k >> 32), b = static_cast<uint32_t>(k);
    rim.triangles.insert(rim.triangles.end(), {a, b, b});
  }
  return rim;
}
}  // namespace

MeshSurface::MeshSurface(const TriangleMesh& mesh) : surface_(mesh), rim_(rim_of(mesh)) {}

double MeshSurface::closest_boundary_point(const double p[3], double out[3]) const {
  if (!has_boundary()) {
    out[0] = p[0], out[1] = p[1], out[2] = p[2];
    return 0;
  }
  return rim_.closest_point(p, out);
}

void MeshSurface::boundary_target(const double p[3], const double t[3], double out[3]) const {
  double x[3] = {p[0], p[1], p[2]};
  for (int i = 0; i < 6; ++i) {
    rim_.closest_point(x, out);
    const double off[3] = {out[0] - p[0], out[1] - p[1], out[2] - p[2]};
    const double along = dot3(off, t);
    // Converged when the curve point is (nearly) in the plane.
    if (std::abs(along) <= 1e-9 * (1 + std::sqrt(dot3(off, off)))) return;
    for (int k = 0; k < 3; ++k) x[k] = out[k] - along * t[k];
  }
}

Sample MeshSurface::sample(const double p[3], const double n[3], double half_length, bool boundary,
                           const double* tangent) const {
  Sample s;
  double d = 0;
  if (boundary && has_boundary()) {
    double c[3];
    if (tangent) boundary_target(p, tangent, c);
    else rim_.closest_point(p, c);
    const double off[3] = {c[0] - p[0], c[1] - p[1], c[2] - p[2]};
    d = dot3(off, n);
    s.source = SampleSource::nearest;
  } else if (double t; surface_.nearest_line_hit(p, n, half_length, t)) {
    d = t;
    s.source = SampleSource::triangle;
  } else {
    double c[3];
    surface_.closest_point(p, c);
    const double off[3] = {c[0] - p[0], c[1] - p[1], c[2] - p[2]};
    d = dot3(off, n);
    s.source = SampleSource::nearest;
  }
  s.clamped = std::abs(d) > half_length;
  s.distance = std::clamp(d, -half_length, half_length);
  return s;
}

double MeshSurface::boundary_offset(const double m[3], const double b[3], const double n[3], double half_length) const {
  if (!has_boundary()) return 0;
  const double t[3] = {n[1] * b[2] - n[2] * b[1], n[2] * b[0] - n[0] * b[2], n[0] * b[1] - n[1] * b[0]};
  double c[3];
  boundary_target(m, t, c);
  const double off[3] = {c[0] - m[0], c[1] - m[1], c[2] - m[2]};
  return std::clamp(dot3(off, b), -half_length, half_length);
}

std::vector<uint8_t> boundary_edges(uint32_t vertex_count, std::span<const uint32_t> triangles) {
  auto t = build_topology(vertex_count, triangles);
  if (!t.ok()) return {};
  const LevelTopology& topo = t.value();
  std::vector<uint8_t> out(topo.edge_count());
  for (uint32_t e = 0; e < topo.edge_count(); ++e) out[e] = topo.twin[topo.edge_half[e]] == kNoHalfEdge;
  return out;
}

double mesh_control_needle(size_t input_faces, uint32_t target_faces) {
  // 0.01 is for inputs far finer than their control mesh, where 0.05's
  // refusals pile up at the end of the run (SimplifyOptions::needle).  At
  // the default 24x reduction 0.05 and 0.01 give the armadillo the same
  // errors (level 4 4.58e-5 both), but 0.01 changed the camel's collapse
  // order round its tail: level 4 4.84e-5 -> 8.25e-5 at error 1e-4, odd
  // vertices cast into the gap between tail and rump (issue 18, camel).
  constexpr double kFineRatio = 32;
  return static_cast<double>(input_faces) > kFineRatio * target_faces ? 0.01 : 0.05;
}

Result<TriangleMesh> control_mesh_from_mesh(const TriangleMesh& input, const MeshSurface& surface, uint32_t target_faces,
                                            MeshControlStats* stats) {
  const MeshInfo before = mesh_counts(input);
  SimplifyStats ss;
  SimplifyOptions so;
  so.needle = mesh_control_needle(input.triangle_count(), target_faces);
  auto simplified = simplify_mesh(input, target_faces, &ss, so);
  if (!simplified.ok()) return simplified.status();
  TriangleMesh m = std::move(simplified).value();
  const MeshInfo after = mesh_info(m);
  // The decoder's limits (a vertex's valence, above all) bind the control
  // mesh: an input whose poles QEM cannot bring under them is refused.
  if (!after.manifold && after.status.code() != ErrorCode::ok)
    return Status(ErrorCode::invalid_argument, "the control mesh simplified from it (" + std::to_string(m.triangle_count()) +
                                                   " triangles) is beyond the format's limits: " + after.status.message() +
                                                   "; a larger --control-faces may help");
  if (!after.manifold || after.genus != before.genus || after.components != before.components ||
      after.boundary_loops != before.boundary_loops)
    return Status(ErrorCode::internal, "the simplified control mesh lost the input's topology (genus " +
                                           std::to_string(before.genus) + " -> " + std::to_string(after.genus) +
                                           ", components " + std::to_string(before.components) + " -> " +
                                           std::to_string(after.components) + ", boundary loops " +
                                           std::to_string(before.boundary_loops) + " -> " +
                                           std::to_string(after.boundary_loops) + ")");
  // QEM's optimal points lie off the surface; the control vertices are even
  // vertices of every level and never move again, so they go on it.
  auto topo = build_topology(static_cast<uint32_t>(m.vertex_count()), m.triangles);
  if (!topo.ok()) return Status(ErrorCode::internal, "the simplified control mesh: " + topo.status().to_string());
  const std::vector<uint8_t>& on_rim = topo.value().vertex_boundary;
  size_t rim_count = 0;
  for (size_t v = 0; v < m.vertex_count(); ++v) {
    const double p[3] = {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
    double c[3];
    if (on_rim[v]) surface.closest_boundary_point(p, c), ++rim_count;
    else surface.closest_point(p, c);
    for (int a = 0; a < 3; ++a) m.positions[3 * v + a] = static_cast<float>(c[a]);
  }
  if (stats) *stats = {ss.faces_before, ss.faces_after, rim_count};
  return m;
}

}  // namespace dbss
