#include "crease_off_points.h"

#include <algorithm>
#include <cmath>


#include "dbss/encoder/point_distances.h"
#include "mesh_geometry.h"

namespace dbss {

using namespace mesh_geometry;

namespace {

// Off the points: over this share of the vertex's mean edge length from
// their plane.  A vertex the projection put on a point is within the
// plane's fit of it (on the cylinder's wall, a chord's sagitta).
constexpr double kOff = 0.25;
constexpr double kSliver = 0.05;
constexpr size_t kNear = 8;
// Steps from the foot to the ring's centroid.
constexpr int kSteps = 4;
// A plane: the variance across under this share of the smaller one along
// (a 64-gon's wall over 8 points: 1e-3; a cube's edge: ~1).
constexpr double kFlat = 0.05;

// The plane of the points nearest q: its centroid and unit normal (false:
// too few points, or they are not a plane: beside a line or a corner).
bool near_plane(const PointIndex& points, const V3& q, V3& centre, V3& normal) {
  const float qf[3] = {static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2])};
  uint32_t near[kNear];
  float dist2[kNear];
  const size_t found = points.nearest_k(qf, kNear, near, dist2);
  if (found < 3) return false;
  const PointPlane plane = fit_plane(points.points(), near, found);
  if (!(plane.variance[0] <= kFlat * plane.variance[1])) return false;
  centre = plane.point, normal = plane.normal;
  return true;
}

}  // namespace

size_t settle_off_points(TriangleMesh& mesh, const LevelTopology& t, const format::Creases& tags,
                         const std::vector<uint32_t>& count, const PointIndex& points) {
  const uint32_t n = t.vertex_count;
  std::vector<uint8_t> boundary(n, 0);
  for (uint32_t h = 0; h < t.triangles.size(); ++h)
    if (t.twin[h] == kNoHalfEdge) boundary[t.triangles[h]] = 1, boundary[t.triangles[next_half(h)]] = 1;
  // Each vertex's fan as (next, previous) corner pairs, counter-clockwise.
  std::vector<std::vector<std::array<uint32_t, 2>>> fan(n);
  for (uint32_t f = 0; f < t.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k)
      fan[t.triangles[3 * f + k]].push_back({t.triangles[3 * f + (k + 1) % 3], t.triangles[3 * f + (k + 2) % 3]});
  size_t moved = 0;
  for (uint32_t v = 0; v < n; ++v) {
    if (boundary[v] || count[v] > 0 || tags.corner[v] != 0 || fan[v].size() < 3) continue;
    const V3 p = pos(mesh, v);
    double length = 0;
    V3 centroid = {0, 0, 0}, area = {0, 0, 0};
    for (const auto& [b, c] : fan[v]) {
      const V3 pb = pos(mesh, b), pc = pos(mesh, c);
      length += std::sqrt(dot(sub(pb, p), sub(pb, p)));
      for (int a = 0; a < 3; ++a) centroid[a] += pb[a] / static_cast<double>(fan[v].size());
      // Sum of b x c over a closed fan: twice the ring's vector area, the
      // same wherever v sits.
      const V3 bc = cross(pb, pc);
      for (int a = 0; a < 3; ++a) area[a] += bc[a];
    }
    length /= static_cast<double>(fan[v].size());
    // Off its nearest point (the projection puts a vertex on one) and off
    // the points' plane.
    const float pf[3] = {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
    const uint32_t nearest = points.nearest(pf);
    const V3 q = {points.points().xyz[3 * size_t{nearest}], points.points().xyz[3 * size_t{nearest} + 1],
                  points.points().xyz[3 * size_t{nearest} + 2]};
    if (!(length > 0) || !(dot(sub(p, q), sub(p, q)) > kOff * kOff * length * length)) continue;
    V3 centre, normal;
    if (!near_plane(points, p, centre, normal)) continue;
    if (!(std::abs(dot(sub(p, centre), normal)) > kOff * length)) continue;
    // Where it goes: the least move onto the plane that leaves its fan
    // facing the way its ring does: its own foot on the plane, else a
    // point on the way from there to its ring's centroid dropped onto the
    // plane of the points nearest that.
    const auto fits = [&](const V3& to) {
      for (const auto& [b, c] : fan[v]) {
        const V3 pb = pos(mesh, b), pc = pos(mesh, c);
        if (!(dot(cross(sub(pb, to), sub(pc, to)), area) > 0) || quality(to, pb, pc) < kSliver) return false;
      }
      return true;
    };
    const double off = dot(sub(p, centre), normal);
    const V3 foot = {p[0] - off * normal[0], p[1] - off * normal[1], p[2] - off * normal[2]};
    V3 to = foot;
    bool ok = fits(to);
    if (!ok && near_plane(points, centroid, centre, normal)) {
      const double h = dot(sub(centroid, centre), normal);
      const V3 inside = {centroid[0] - h * normal[0], centroid[1] - h * normal[1], centroid[2] - h * normal[2]};
      for (int k = 1; k <= kSteps && !ok; ++k) {
        const double s = static_cast<double>(k) / kSteps;
        for (int a = 0; a < 3; ++a) to[a] = foot[a] + s * (inside[a] - foot[a]);
        ok = fits(to);
      }
    }
    if (!ok) continue;
    for (int a = 0; a < 3; ++a) mesh.positions[3 * size_t{v} + a] = static_cast<float>(to[a]);
    ++moved;
  }
  return moved;
}

}  // namespace dbss
