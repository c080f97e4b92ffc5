#include "dbss/encoder/sampling.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dbss/encoder/crease_lines.h"
#include "dbss/encoder/point_distances.h"

namespace dbss {

namespace {
using V = Eigen::Vector3d;
// Two points are of one sheet when their offsets along the sampling line
// differ by at most this times the sum of their distances from it.
constexpr double kSteep = 3;
// The fallback plane's points when the cylinder holds two sheets.
constexpr size_t kPlanePoints = 16;
constexpr double kAnchorReach = 1.5;

// Ray-triangle intersection (Moller-Trumbore) for the full line p + t n.
bool line_hits(const V& p, const V& n, const V& a, const V& b, const V& c, double& t) {
  const V e1 = b - a, e2 = c - a;
  const V h = n.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-14 * e1.norm() * e2.norm()) return false;
  const double inv = 1.0 / det;
  const V s = p - a;
  const double u = inv * s.dot(h);
  if (u < 0 || u > 1) return false;
  const V q = s.cross(e1);
  const double v = inv * n.dot(q);
  if (v < 0 || u + v > 1) return false;
  t = inv * e2.dot(q);
  return true;
}

// Next to a crease (one-sided sampling on): the surface along the line as
// two planes meeting at the feature.  The kWedgePoints points nearest p are
// split by their normals into two sides; when the sides meet at more than
// the one-sided angle and each is flat, the line's hit on each side's plane
// counts only where it lies on that side's half of the wedge (beyond the
// other plane, on the side its own points are); of two such, the nearer.
// A fitted height field over both sides rounds the feature within a point
// spacing or two of it (measured on the cube: the level-3 vertices there
// sat 0.005-0.01 inside, 70% of the level's error); the planes do not.
constexpr size_t kWedgePoints = 32;
bool wedge_hit(const PointIndex& index, const double pd[3], const double nd[3], const PointSides& sides, double& t_out) {
  const PointCloud& pc = index.points();
  const float q[3] = {static_cast<float>(pd[0]), static_cast<float>(pd[1]), static_cast<float>(pd[2])};
  uint32_t idx[kWedgePoints];
  float dist2[kWedgePoints];
  const size_t found = index.nearest_k(q, kWedgePoints, idx, dist2);
  if (found < kWedgePoints) return false;
  const double radius = std::sqrt(double{dist2[found - 1]});
  const auto normal = [&](uint32_t i) {
    const float* m = sides.normals->data() + 3 * size_t{i};
    return V(m[0], m[1], m[2]);
  };
  const auto least_aligned = [&](const V& s) {
    V best = normal(idx[0]);
    double best_c = INFINITY;
    for (size_t j = 0; j < found; ++j)
      if (const double c = std::abs(normal(idx[j]).dot(s)); c < best_c) best_c = c, best = normal(idx[j]);
    return best;
  };
  V seed[2];
  seed[1] = least_aligned(normal(idx[0]));
  seed[0] = least_aligned(seed[1]);
  if (std::abs(seed[0].dot(seed[1])) >= sides.min_cos) return false;  // one sheet here
  std::vector<uint32_t> group[2];
  for (size_t j = 0; j < found; ++j) {
    const V m = normal(idx[j]);
    group[std::abs(m.dot(seed[0])) >= std::abs(m.dot(seed[1])) ? 0 : 1].push_back(idx[j]);
  }
  PointPlane fit[2];
  for (int round = 0; round < 2; ++round) {
    for (int k = 0; k < 2; ++k) {
      if (group[k].size() < 6) return false;
      fit[k] = fit_plane(pc, group[k].data(), group[k].size());
    }
    if (round == 1) break;
    group[0].clear(), group[1].clear();
    for (size_t j = 0; j < found; ++j) {
      const V x(pc.xyz[3 * size_t{idx[j]}], pc.xyz[3 * size_t{idx[j]} + 1], pc.xyz[3 * size_t{idx[j]} + 2]);
      double d[2];
      for (int k = 0; k < 2; ++k)
        d[k] = std::abs((x - V(fit[k].point[0], fit[k].point[1], fit[k].point[2])).dot(V(fit[k].normal[0], fit[k].normal[1], fit[k].normal[2])));
      group[d[0] <= d[1] ? 0 : 1].push_back(idx[j]);
    }
  }
  V c[2], m[2];
  for (int k = 0; k < 2; ++k) {
    // Flat sides, each a patch (not the strip of points along the line).
    if (std::sqrt(std::max(0.0, fit[k].variance[0])) > 0.05 * radius) return false;
    if (fit[k].variance[1] < std::pow(0.1 * radius, 2)) return false;
    c[k] = V(fit[k].point[0], fit[k].point[1], fit[k].point[2]), m[k] = V(fit[k].normal[0], fit[k].normal[1], fit[k].normal[2]);
  }
  if (std::abs(m[0].dot(m[1])) >= sides.min_cos) return false;
  const V p(pd[0], pd[1], pd[2]), n(nd[0], nd[1], nd[2]);
  bool hit = false;
  for (int k = 0; k < 2; ++k) {
    const double nm = n.dot(m[k]);
    if (std::abs(nm) < 0.2) continue;  // the line runs along this side
    const double t = (c[k] - p).dot(m[k]) / nm;
    const V x = p + t * n;
    const int o = 1 - k;
    // On this side's half-plane: on the same side of the other plane as this side's points.
    if ((x - c[o]).dot(m[o]) * (c[k] - c[o]).dot(m[o]) < 0) continue;
    if (!hit || std::abs(t) < std::abs(t_out)) t_out = t, hit = true;
  }
  return hit;
}
}  // namespace

Sample sample_displacement(const PointIndex& index, const double p[3], const double n[3], double radius,
                           double half_length, bool fit) {
  SampleScratch scratch;
  return sample_displacement(index, p, n, radius, half_length, scratch, fit);
}

Sample sample_displacement(const PointIndex& index, const double pd[3], const double nd[3], double radius,
                           double half_length, SampleScratch& scratch, bool fit, const PointSides* sides, bool widen) {
  const PointCloud& pc = index.points();
  const V p(pd[0], pd[1], pd[2]), n(nd[0], nd[1], nd[2]);
  const auto point = [&](uint32_t i) { return V(pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]); };
  Sample out;
  // Points inside the cylinder: horizontal distance to the line under
  // `radius`, vertical offset along it under `half_length`.
  std::vector<uint32_t>& near = scratch.near;
  const PointSides* const original_sides = sides;
  const float q[3] = {static_cast<float>(pd[0]), static_cast<float>(pd[1]), static_cast<float>(pd[2])};
  index.within(q, static_cast<float>(std::sqrt(radius * radius + half_length * half_length)), near);
  using Cand = SampleScratch::Candidate;
  std::vector<Cand>& cyl = scratch.cylinder;
  cyl.clear();
  // One-sided: the points beside a feature line often belong to the other
  // side, so the line's own side may need a wider cylinder; with too few
  // there either, both sides (and the fit from both).
  for (int pass = sides ? 0 : 2; pass < 3 && cyl.size() < 3; ++pass) {
    const double r = pass == 1 ? 2 * radius : radius;
    if (pass == 1) index.within(q, static_cast<float>(std::sqrt(r * r + half_length * half_length)), near);
    if (pass == 2 && sides) {
      sides = nullptr;
      index.within(q, static_cast<float>(std::sqrt(radius * radius + half_length * half_length)), near);
    }
    cyl.clear();
    for (uint32_t i : near) {
      if (sides && !sides->agrees(i, nd)) continue;
      const V x = point(i);
      const double t = (x - p).dot(n);
      const double h = (x - p - t * n).norm();
      if (h < r && std::abs(t) < half_length) cyl.push_back({h, t, i});
    }
  }
  auto finish = [&](double d, SampleSource src) {
    out.source = src;
    // The hit found the sheet; the fitted surface around it says where the
    // points' surface is, without the noise of which points the line met.
    // A fit that leaves the cylinder the hit was found in (its neighbourhood
    // reaches past the cylinder on a sparse scan) is not trusted over it.
    if (fit) {
      const SurfaceFit f = fit_height(index, pd, nd, d, kFitPoints, scratch.fit, sides, widen);
      if (f.ok && (std::abs(f.height) <= half_length || std::abs(d) > half_length))
        d = f.height, out.fitted = true, out.spread = f.spread;
    }
    out.clamped = std::abs(d) > half_length;
    out.distance = std::clamp(d, -half_length, half_length);
    return out;
  };
  if (const PointSides* wedge = original_sides; wedge && wedge->wedge && (!wedge->lines || wedge->lines->near(pd))) {
    double t = 0;
    if (wedge_hit(index, pd, nd, *wedge, t) && std::abs(t) <= half_length) {
      out.source = SampleSource::plane;
      out.fitted = true;
      out.wedge = true;
      out.distance = t;
      return out;
    }
  }
  if (cyl.size() >= 3) {
    // Candidate triangles from the points nearest the line; the hit nearest
    // to the vertex wins, so the closest sheet of a thin part is taken.  The
    // candidates are the sheet's: of the points about as near the line as
    // the 7 nearest (within kAnchorReach of the 7th: some of them on each
    // face), the one nearest the vertex along it anchors the sheet, and a point counts
    // when a surface through both could pass (rising at most kSteep times
    // its run, about 72 degrees to the plane normal to the line).  Else,
    // where a thin part's other face is as near the line as its own (the
    // fandisk's flange: faces 0.1 apart, points 0.005 apart), triangles of
    // two points of one face and one of the other hit between the faces, on
    // neither, and won as the nearest (level 1 of the fandisk: odd vertices
    // on the face sampled 0.03-0.05 inside it).
    const size_t first = std::min<size_t>(cyl.size(), 7);
    std::partial_sort(cyl.begin(), cyl.begin() + first, cyl.end(),
                      [](const Cand& a, const Cand& b) { return a.horizontal < b.horizontal; });
    Cand anchor = cyl[0];
    for (const Cand& x : cyl)
      if (x.horizontal <= kAnchorReach * cyl[first - 1].horizontal && std::abs(x.vertical) < std::abs(anchor.vertical)) anchor = x;
    const auto on_sheet = [&](const Cand& c) {
      return std::abs(c.vertical - anchor.vertical) <= kSteep * (c.horizontal + anchor.horizontal);
    };
    // One sheet (every point of the cylinder on it, as on any smooth shape
    // whose curvature radius is over the cylinder's): the candidates and
    // the fallback plane's points are the same as without the test.  (Tested
    // first: stable_partition allocates a buffer, and this runs per sample.)
    const bool one_sheet = std::all_of(cyl.begin(), cyl.end(), on_sheet);
    const auto sheet_end = one_sheet ? cyl.end() : std::stable_partition(cyl.begin(), cyl.end(), on_sheet);
    const size_t sheet = static_cast<size_t>(sheet_end - cyl.begin());
    size_t m = first;
    if (!one_sheet) {
      m = std::min<size_t>(sheet, 7);
      std::partial_sort(cyl.begin(), cyl.begin() + m, sheet_end,
                        [](const Cand& a, const Cand& b) { return a.horizontal < b.horizontal; });
    }
    double best = 0;
    bool hit = false;
    for (size_t i = 0; i < m; ++i)
      for (size_t j = i + 1; j < m; ++j)
        for (size_t k = j + 1; k < m; ++k) {
          double t;
          if (line_hits(p, n, point(cyl[i].point), point(cyl[j].point), point(cyl[k].point), t) &&
              std::abs(t) < half_length && (!hit || std::abs(t) < std::abs(best)))
            best = t, hit = true;
        }
    if (hit) return finish(best, SampleSource::triangle);
    // Plane through the cylinder's points; with two sheets, through the
    // kPlanePoints of the vertex's sheet nearest the line (the sheet's cone
    // takes in the other face's points farther out).
    size_t count = cyl.size();
    if (!one_sheet) {
      count = std::min<size_t>(sheet, kPlanePoints);
      std::partial_sort(cyl.begin(), cyl.begin() + count, sheet_end,
                        [](const Cand& a, const Cand& b) { return a.horizontal < b.horizontal; });
    }
    V c = V::Zero();
    for (size_t i = 0; i < count; ++i) c += point(cyl[i].point);
    c /= static_cast<double>(count);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (size_t i = 0; i < count; ++i) cov += (point(cyl[i].point) - c) * (point(cyl[i].point) - c).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const V m3 = eig.eigenvectors().col(0);
    const double nm = n.dot(m3);
    if (count >= 3 && std::abs(nm) > 0.3) return finish((c - p).dot(m3) / nm, SampleSource::plane);
  }
  // Nearest point's offset along the normal.
  const uint32_t i = index.nearest(q);
  const V x(pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]);
  return finish((x - p).dot(n), SampleSource::nearest);
}

}  // namespace dbss
