#include "dbss/encoder/tube_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "mesh_geometry.h"

namespace dbss {

namespace {

using mesh_geometry::V3, mesh_geometry::sub, mesh_geometry::dot, mesh_geometry::cross;

double len(V3 a) { return std::sqrt(dot(a, a)); }
V3 unit(V3 a) {
  const double l = len(a);
  return l > 0 ? V3{a[0] / l, a[1] / l, a[2] / l} : V3{0, 0, 0};
}

// Steps the curve is followed in to measure its length and carry the
// rings' frame along it.
constexpr int kCurveSteps = 256;
// The added points keep this many spacings from the scan's own.
constexpr double kClearance = 0.75;

// The rings' radius at a rim: the tube's (PointRim::tube_radius), never
// more than the rim's mean radius.  A cut that crosses the tube obliquely
// leaves a rim longer one way (0.45-0.79 of mean radius on the triple
// torus's tubes of 0.3), and rings of that radius were fatter than the
// tube they stand for: the rebuilt surface met the next torus (two
// components, or genus 5) and the join was refused.
// Only a rim that cuts across a tube's wall has a tube direction: round a
// hole in a wall (PointRim::wall near 1) the normals all lie along the
// axis, their least spread is noise, and tube_radius comes out about 0.64
// of the mean radius; such a rim keeps its mean radius.  Tube ends on the
// hole sweep have walls of 0.2-0.6.
constexpr double kMaxTubeWall = 0.8;
double ring_radius(const PointRim& r) {
  return r.tube_radius > 0 && r.wall < kMaxTubeWall ? std::min(r.radius, r.tube_radius) : r.radius;
}

// The Hermite curve of hole_bridge.cpp and point_rims.cpp's join test, from
// a's centre to b's: it leaves a against a's axis and enters b along b's
// (each axis points into the scanned tube its rim ends), tangents as long
// as the chord.
struct Curve {
  V3 a, b, ta, tb;
  V3 at(double t) const {
    const double h00 = 2 * t * t * t - 3 * t * t + 1, h10 = t * t * t - 2 * t * t + t;
    const double h01 = -2 * t * t * t + 3 * t * t, h11 = t * t * t - t * t;
    return {h00 * a[0] + h10 * ta[0] + h01 * b[0] + h11 * tb[0], h00 * a[1] + h10 * ta[1] + h01 * b[1] + h11 * tb[1],
            h00 * a[2] + h10 * ta[2] + h01 * b[2] + h11 * tb[2]};
  }
  V3 tangent(double t) const {
    const double d00 = 6 * t * t - 6 * t, d10 = 3 * t * t - 4 * t + 1, d01 = -6 * t * t + 6 * t, d11 = 3 * t * t - 2 * t;
    return unit({d00 * a[0] + d10 * ta[0] + d01 * b[0] + d11 * tb[0], d00 * a[1] + d10 * ta[1] + d01 * b[1] + d11 * tb[1],
                 d00 * a[2] + d10 * ta[2] + d01 * b[2] + d11 * tb[2]});
  }
};

}  // namespace

TubePoints sample_cut_tubes(const PointIndex& index, const std::vector<PointRim>& rims,
                            const std::vector<std::pair<size_t, size_t>>& pairs, double spacing) {
  TubePoints out;
  out.points = index.points();
  if (!(spacing > 0)) return out;
  const PointCloud& pc = index.points();
  const bool has_normals = pc.normals.size() == pc.xyz.size();
  if (!has_normals) out.points.normals.clear();
  for (const auto& [ia, ib] : pairs) {
    const PointRim &ra = rims[ia], &rb = rims[ib];
    const double chord = len(sub(rb.centre, ra.centre));
    if (!(chord > 0)) continue;
    Curve c{ra.centre, rb.centre, {}, {}};
    for (int k = 0; k < 3; ++k) c.ta[k] = -chord * ra.axis[k], c.tb[k] = chord * rb.axis[k];
    // Arc length along the curve, and a frame carried along it without
    // twisting (each step's first axis is the last one's, made
    // perpendicular to the new tangent).
    std::array<double, kCurveSteps + 1> arc{};
    std::array<V3, kCurveSteps + 1> e1{};
    {
      const V3 t0 = c.tangent(0);
      const V3 helper = std::abs(t0[0]) < 0.6 ? V3{1, 0, 0} : V3{0, 1, 0};
      e1[0] = unit(cross(t0, helper));
      V3 prev = c.at(0);
      for (int s = 1; s <= kCurveSteps; ++s) {
        const double t = static_cast<double>(s) / kCurveSteps;
        const V3 p = c.at(t), tan = c.tangent(t);
        arc[s] = arc[s - 1] + len(sub(p, prev));
        prev = p;
        const double along = dot(e1[s - 1], tan);
        e1[s] = unit({e1[s - 1][0] - along * tan[0], e1[s - 1][1] - along * tan[1], e1[s - 1][2] - along * tan[2]});
      }
    }
    const double length = arc[kCurveSteps];
    // A tube this scan lost is a small part of it (the bridging stage's
    // pairs are under 6 radii apart): one that would take more points than
    // the scan has is not one, and a non-finite size (a NaN radius passes
    // every comparison of the pairing) is no size.  This also keeps the
    // ring counts below in int.
    const double expected = (length / spacing + 1) * (2 * std::numbers::pi * std::max(ra.radius, rb.radius) / spacing + 8);
    if (!std::isfinite(expected) || !(ra.radius > 0) || !(rb.radius > 0) || expected > static_cast<double>(pc.size())) continue;
    const int rings = std::max(1, static_cast<int>(std::ceil(length / spacing)));
    const size_t before = out.points.size();
    for (int r = 0; r <= rings; ++r) {
      const double s_len = length * r / rings;
      const int step = std::min<int>(kCurveSteps - 1, static_cast<int>(std::upper_bound(arc.begin(), arc.end(), s_len) - arc.begin()) - 1);
      const double f = arc[step + 1] > arc[step] ? (s_len - arc[step]) / (arc[step + 1] - arc[step]) : 0;
      const double t = (step + std::clamp(f, 0.0, 1.0)) / kCurveSteps;
      const V3 centre = c.at(t), tan = c.tangent(t);
      V3 u = e1[step];
      const double along = dot(u, tan);
      u = unit({u[0] - along * tan[0], u[1] - along * tan[1], u[2] - along * tan[2]});
      const V3 v = cross(tan, u);
      const double radius = (1 - s_len / length) * ring_radius(ra) + s_len / length * ring_radius(rb);
      const int around = std::max(8, static_cast<int>(std::ceil(2 * std::numbers::pi * radius / spacing)));
      // Alternate rings half a step round: a staggered sampling, like a
      // scan's, not a grid the carving's cells could fall between.
      const double shift = r % 2 ? 0.5 : 0.0;
      for (int k = 0; k < around; ++k) {
        const double phi = 2 * std::numbers::pi * (k + shift) / around;
        const double cs = std::cos(phi), sn = std::sin(phi);
        const float q[3] = {static_cast<float>(centre[0] + radius * (cs * u[0] + sn * v[0])),
                            static_cast<float>(centre[1] + radius * (cs * u[1] + sn * v[1])),
                            static_cast<float>(centre[2] + radius * (cs * u[2] + sn * v[2]))};
        const uint32_t near = index.nearest(q);
        double d2 = 0;
        for (int a = 0; a < 3; ++a) d2 += std::pow(q[a] - double{pc.xyz[3 * near + a]}, 2);
        if (d2 < kClearance * kClearance * spacing * spacing) continue;
        out.points.xyz.insert(out.points.xyz.end(), q, q + 3);
        // A cloud with normals keeps three per point: the ring's own,
        // pointing out of the tube.
        if (has_normals)
          for (int a = 0; a < 3; ++a) out.points.normals.push_back(static_cast<float>(cs * u[a] + sn * v[a]));
      }
    }
    const size_t added = out.points.size() - before;
    if (added == 0) continue;
    ++out.tubes;
    out.added += added;
    // Each point stands for a square of the spacing's side (the spacing is
    // the scan's, from its density).
    out.area += static_cast<double>(added) * spacing * spacing;
  }
  return out;
}

}  // namespace dbss
