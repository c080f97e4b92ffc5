#include "dbss/encoder/point_rims.h"
#include "union_find.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <tuple>

#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/triangle_tree.h"
#include "mesh_geometry.h"

namespace dbss {

namespace {

using mesh_geometry::V3, mesh_geometry::sub, mesh_geometry::dot, mesh_geometry::cross;

// Neighbours a point is judged by (itself included).
constexpr size_t kNeighbours = 24;
// A point is on a rim when its neighbours, seen in its tangent plane, leave
// an empty sector wider than this.  Scans are not blue noise: among 15
// neighbours of a random sample a third of the circle is empty at one
// point in five; 150 degrees among 23 at about one in 5,000.  At a rim
// the gap is about 180 degrees.
constexpr double kRimGap = 5.0 * std::numbers::pi / 6.0;
// A rim runs (most of the way) round its centre: of 12 sectors of 30
// degrees round its axis, at least RimOptions::min_sectors (8) hold some of
// its points (an arc, the edge of a patch, is not the end of a tube; a
// sparse scan's rim has gaps).  Fewer than RimOptions::min_points (8)
// boundary points are a ragged spot in a sparse scan, not the edge of an
// opening.
constexpr int kSectors = 12;
// The largest mean wall of a pair taken for a tube's two ends
// (kTubeEndMaxWall, point_rims.h: the bound hole_bridge.cpp builds tubes
// under), and the least cosine between the gap and a facing rim's axis
// (its doubtful rule), on the points instead of a sheet's loops.  Cut
// tubes' ends on the hole sweep: mean walls 0.20-0.52; two arcs of one
// hole's rim in a sparse scan, taken for two rims: 0.58.  The rims' walls
// move by 0.1-0.2 with a few points more or less, so the margin is thin
// both ways.
constexpr double kMinFacing = 0.4;
// Longest gap between a pair's centres, in larger radii.
constexpr double kMaxGap = 6;

double len(V3 a) { return std::sqrt(dot(a, a)); }
V3 unit(V3 a) {
  const double l = len(a);
  return l > 0 ? V3{a[0] / l, a[1] / l, a[2] / l} : V3{0, 0, 0};
}
V3 point(const PointCloud& pc, size_t i) { return {pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]}; }

// Two unit vectors completing n to an orthonormal basis.
std::pair<V3, V3> tangents(V3 n) {
  const V3 helper = std::abs(n[0]) < 0.6 ? V3{1, 0, 0} : V3{0, 1, 0};
  const V3 e1 = unit(cross(n, helper));
  return {e1, cross(n, e1)};
}

}  // namespace

std::vector<PointRim> find_point_rims(const PointIndex& index, size_t max_points, const RimOptions& options) {
  return link_rims(find_rim_points(index, max_points), options);
}

RimPoints find_rim_points(const PointIndex& index, size_t max_points) {
  const PointCloud& pc = index.points();
  const size_t n = pc.size();
  RimPoints out;
  if (n < kNeighbours || max_points < kNeighbours) return out;
  if (n > max_points) {
    // A larger cloud is judged by every stride-th point with its own index,
    // as a sparser scan of the same surface: the neighbourhoods and the
    // links between boundary points grow together.  (Examining a share of
    // the points against the full cloud's neighbours, and linking them over
    // `stride` times their reach, joined the two ends of a cut band.)
    const size_t stride = (n + max_points - 1) / max_points;
    PointCloud share;
    share.xyz.reserve(3 * (n / stride + 1));
    for (size_t i = 0; i < n; i += stride) share.xyz.insert(share.xyz.end(), &pc.xyz[3 * i], &pc.xyz[3 * i] + 3);
    const PointIndex share_index(share);
    return find_rim_points(share_index, max_points);
  }
  // The boundary points: where each is, its surface normal, and the
  // direction (in its tangent plane) of the empty sector, into the opening.
  PointCloud& edge = out.edge;
  std::vector<V3>&normal = out.normal, &into = out.into;
  std::vector<double>& reach_of = out.reach;  // each boundary point's distance to its farthest neighbour
  uint32_t nb[kNeighbours];
  float d2[kNeighbours];
  std::vector<double> angle;
  std::vector<uint32_t> near;
  for (size_t i = 0; i < n; ++i) {
    const float* q = &pc.xyz[3 * i];
    const size_t k = index.nearest_k(q, kNeighbours, nb, d2);
    if (k < kNeighbours) continue;
    const PointPlane plane = fit_plane(pc, nb, k);
    const auto [e1, e2] = tangents(plane.normal);
    const V3 p = point(pc, i);
    angle.clear();
    for (size_t j = 0; j < k; ++j) {
      const V3 d = sub(point(pc, nb[j]), p);
      const double x = dot(d, e1), y = dot(d, e2);
      if (x != 0 || y != 0) angle.push_back(std::atan2(y, x));
    }
    if (angle.size() < 3) continue;
    std::sort(angle.begin(), angle.end());
    double widest = angle.front() + 2 * std::numbers::pi - angle.back(), middle = angle.back() + 0.5 * widest;
    for (size_t j = 1; j < angle.size(); ++j)
      if (angle[j] - angle[j - 1] > widest) widest = angle[j] - angle[j - 1], middle = angle[j - 1] + 0.5 * widest;
    if (widest <= kRimGap) continue;
    // Where the density falls off (a scanner's far side; a sampling that
    // crowds one side of a tube), the nearest points all lie on the dense
    // side and leave a sector empty that is not.  A rim's sector is empty
    // farther out: no point near the tangent plane within 1.5 times the
    // neighbourhood's radius inside it (its middle two thirds).
    const double reach = 1.5 * std::sqrt(double{d2[k - 1]});
    index.within(q, static_cast<float>(reach), near);
    bool empty = true;
    for (uint32_t j : near) {
      const V3 d = sub(point(pc, j), p);
      const double x = dot(d, e1), y = dot(d, e2);
      if (std::abs(dot(d, plane.normal)) > 0.5 * reach || (x == 0 && y == 0)) continue;
      const double off = std::remainder(std::atan2(y, x) - middle, 2 * std::numbers::pi);
      if (std::abs(off) < widest / 3) {
        empty = false;
        break;
      }
    }
    if (!empty) continue;
    edge.xyz.insert(edge.xyz.end(), q, q + 3);
    normal.push_back(plane.normal);
    reach_of.push_back(std::sqrt(double{d2[k - 1]}));
    const double c = std::cos(middle), s = std::sin(middle);
    into.push_back({c * e1[0] + s * e2[0], c * e1[1] + s * e2[1], c * e1[2] + s * e2[2]});
  }
  return out;
}

std::vector<PointRim> link_rims(const RimPoints& points, const RimOptions& options) {
  const PointCloud& edge = points.edge;
  const std::vector<V3>&normal = points.normal, &into = points.into;
  const std::vector<double>& reach_of = points.reach;
  std::vector<PointRim> rims;
  std::vector<uint32_t> near;
  const size_t m = edge.size();
  if (m < options.min_points) return rims;
  // Link boundary points closer than twice their neighbourhoods' radius
  // (about three local spacings each), so a sparse stretch of rim stays
  // one.
  Sets sets(m);
  {
    const PointIndex edge_index(edge);
    for (size_t i = 0; i < m; ++i) {
      edge_index.within(&edge.xyz[3 * i], static_cast<float>(options.link * reach_of[i]), near);
      for (uint32_t j : near) sets.join(static_cast<uint32_t>(i), j);
    }
  }
  std::vector<std::vector<uint32_t>> groups(m);
  for (size_t i = 0; i < m; ++i) groups[sets.find(static_cast<uint32_t>(i))].push_back(static_cast<uint32_t>(i));
  for (const std::vector<uint32_t>& g : groups) {
    if (g.size() < options.min_points) continue;
    const PointPlane plane = fit_plane(edge, g.data(), g.size());
    PointRim r;
    r.centre = plane.point;
    r.axis = plane.normal;
    r.points = g.size();
    {
      // The tube's own direction is the one its wall's normals are all
      // square to: the least spread of the normals (each taken both ways,
      // so they centre on zero).  Each rim point lies a tube's radius from
      // the line along it through the centre, however oblique the cut.
      PointCloud both;
      both.xyz.reserve(6 * g.size());
      std::vector<uint32_t> all(2 * g.size());
      for (uint32_t i : g)
        for (double sign : {1.0, -1.0})
          for (int a = 0; a < 3; ++a) both.xyz.push_back(static_cast<float>(sign * normal[i][a]));
      std::iota(all.begin(), all.end(), 0u);
      const V3 along = fit_plane(both, all.data(), all.size()).normal;
      for (uint32_t i : g) {
        const V3 d = sub(point(edge, i), r.centre);
        const double t = dot(d, along);
        r.tube_radius += len({d[0] - t * along[0], d[1] - t * along[1], d[2] - t * along[2]}) / static_cast<double>(g.size());
      }
    }
    V3 opening{0, 0, 0};
    for (uint32_t i : g) {
      r.radius += len(sub(point(edge, i), r.centre)) / static_cast<double>(g.size());
      r.wall += std::abs(dot(normal[i], r.axis)) / static_cast<double>(g.size());
      for (int a = 0; a < 3; ++a) opening[a] += into[i][a];
    }
    // The axis points away from the opening: against the way the rim's
    // empty sectors face.
    if (dot(opening, r.axis) > 0)
      for (double& a : r.axis) a = -a;
    // All the way round?
    const auto [e1, e2] = tangents(r.axis);
    bool sector[kSectors] = {};
    for (uint32_t i : g) {
      const V3 d = sub(point(edge, i), r.centre);
      const double t = std::atan2(dot(d, e2), dot(d, e1)) + std::numbers::pi;
      sector[std::min(kSectors - 1, static_cast<int>(t / (2 * std::numbers::pi) * kSectors))] = true;
    }
    r.sectors = static_cast<int>(std::count(sector, sector + kSectors, true));
    if (r.sectors < options.min_sectors || r.radius <= 0) continue;
    rims.push_back(r);
  }
  return rims;
}

std::vector<std::pair<size_t, size_t>> tube_end_pairs(const std::vector<PointRim>& rims, double max_wall) {
  std::vector<std::tuple<double, size_t, size_t>> scored;
  for (size_t a = 0; a < rims.size(); ++a)
    for (size_t b = a + 1; b < rims.size(); ++b) {
      const PointRim &ra = rims[a], &rb = rims[b];
      const V3 d = sub(rb.centre, ra.centre);
      const double gap = len(d);
      const double big = std::max(ra.radius, rb.radius), small = std::min(ra.radius, rb.radius);
      if (gap <= 0 || small < 0.5 * big || gap > kMaxGap * big) continue;
      if (0.5 * (ra.wall + rb.wall) >= max_wall) continue;
      // Each axis points away from its opening, so across a gap the two
      // point apart: a faces b when the gap runs against a's axis.
      const V3 u{d[0] / gap, d[1] / gap, d[2] / gap};
      const bool a_faces = dot(u, ra.axis) < -kMinFacing, b_faces = dot(u, rb.axis) > kMinFacing;
      const bool half_facing = (a_faces && dot(u, rb.axis) > -0.5) || (b_faces && dot(u, ra.axis) < 0.5);
      if (half_facing) scored.emplace_back(gap / (ra.radius + rb.radius), a, b);
    }
  std::sort(scored.begin(), scored.end());
  std::vector<uint8_t> used(rims.size(), 0);
  std::vector<std::pair<size_t, size_t>> pairs;
  for (const auto& [score, a, b] : scored)
    if (!used[a] && !used[b]) used[a] = used[b] = 1, pairs.emplace_back(a, b);
  return pairs;
}

bool rims_face_as_one_tube(const PointRim& a, const PointRim& b, double same_tube) {
  const V3 d = sub(b.centre, a.centre);
  const double gap = len(d);
  if (gap <= 0) return false;
  const V3 u{d[0] / gap, d[1] / gap, d[2] / gap};
  const double small = std::min(a.tube_radius, b.tube_radius), big = std::max(a.tube_radius, b.tube_radius);
  return dot(u, a.axis) < -kMinFacing && dot(u, b.axis) > kMinFacing && small >= same_tube * big;
}

namespace {

// The two places a join of a and b passes through at its middle: the
// chord's, and hole_bridge.cpp's Hermite curve's (it leaves a against a's
// axis and enters b along b's, so a bent tube's middle lies off the chord).
std::pair<V3, V3> gap_middles(const PointRim& a, const PointRim& b) {
  const V3 chord_mid{0.5 * (a.centre[0] + b.centre[0]), 0.5 * (a.centre[1] + b.centre[1]),
                     0.5 * (a.centre[2] + b.centre[2])};
  const double gap = len(sub(b.centre, a.centre));
  V3 curve_mid = chord_mid;
  for (int c = 0; c < 3; ++c) curve_mid[c] -= 0.125 * gap * (a.axis[c] + b.axis[c]);
  return {chord_mid, curve_mid};
}

}  // namespace

bool surface_joins(const TriangleMesh& closed_surface, const PointRim& a, const PointRim& b) {
  const auto [chord_mid, curve_mid] = gap_middles(a, b);
  return inside_mesh(closed_surface, chord_mid) || inside_mesh(closed_surface, curve_mid);
}

double gap_clearance(const TriangleTree& surface, const PointRim& a, const PointRim& b) {
  const double tube = std::max(a.tube_radius, b.tube_radius);
  if (!(tube > 0)) return 0;
  const auto [chord_mid, curve_mid] = gap_middles(a, b);
  return std::min(surface.distance(chord_mid.data()), surface.distance(curve_mid.data())) / tube;
}

}  // namespace dbss
