#include "dbss/encoder/sampling.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dbss/encoder/crease_lines.h"
#include "dbss/encoder/facet_hit.h"
#include "dbss/encoder/point_distances.h"
#include "dbss/encoder/residual_hit.h"

namespace dbss {

namespace {
using V = Eigen::Vector3d;
// Two points are of one sheet when their offsets along the sampling line
// differ by at most this times the sum of their distances from it.
constexpr double kSteep = 3;
// The same when every candidate's own normal agrees with the line's
// (one-sided sampling next to creases, PointSides): a sheet then leans at
// most 30 degrees across the line (a slope of 0.58); 1 leaves room for the
// normals' error.  At kSteep the two faces of a thin part (the fandisk's
// flange, 0.04 thick, its normals parallel) were one sheet wherever the 7
// points nearest the line were mostly the other face's: the triangles of
// two points of one face and one of the other hit between the faces, and
// the level-1 odd vertex went 0.016-0.018 inside (the fandisk's level-3
// Hausdorff point at seeds 1 and 2, bench/crease_bench.md, fourteenth
// session).
constexpr double kSteepOneSided = 1;
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
// sides meeting at the feature, two along a line (either a plane, or a
// quadric beside a curved wall), three planes at a corner.  The
// kWedgePoints points nearest p are split into sides, each point on the
// nearest of the sides; when the sides meet at more than the
// one-sided angle and each is flat (or a close quadric),
// the line's hit on each side's plane counts only where it lies on that
// side's part of the wedge (on the same side of every other plane as its
// own points); of those, the nearest.  A fitted height field over both
// sides rounds the feature within a point spacing or two of it (measured
// on the cube: the level-3 vertices there sat 0.005-0.01 inside, 70% of
// the level's error); the planes do not.
constexpr size_t kWedgePoints = 32;
// The sides' planes are refitted until no point changes side (at most
// this many fits).  They once were split by the points' normals and
// refitted once: the normals of points within a spacing or two of the
// feature blend both sides (the cube: (-0.42, -0.85, 0.32) at 0.01 from the
// edge x = y = 1), so the first fit leaned and one refit left it leaning
// (level-1 crease samples 0.004-0.02 inside the cube, 2.1e-4 of the
// diagonal on average; their vertices were most of level 1's rise).
constexpr int kWedgeRounds = 8;
// Points a side's plane needs.  Fewer than the six it once needed: at a
// corner a side may show only a few (the cube's level 3, 0.05 from a corner:
// 5 of 32 points on the third face).
constexpr size_t kSidePoints = 4;
// A side narrower than a tenth of the radius: at least this wide (over
// the radius), its points this close to its plane (over its width, about
// the tangent of how far the plane may tilt).
constexpr double kStripWidth = 0.02, kStripTilt = 0.05;
// A seed plane's points: within this much of the neighbourhood's radius.
constexpr double kSeedBand = 0.02;
// A side's hit counts as on its part of the wedge up to this far (over the
// radius) beyond another side's plane.  At the seeds' band (0.02) the
// cylinder's, fandisk's and anchor's worst level-3 Hausdorff rose (1.09,
// 1.75, 1.82% at their worst seeds): hits just past a neighbouring side
// taken near corners.
constexpr double kInsideSlack = 0.002;

// A side of the wedge: a plane (c, m), or beside a curved wall a quadric
// height field over that plane, w = q(u, v) in the frame (e1, e2, m) at c.
struct Side {
  V c = V::Zero(), m = V::Zero(), e1 = V::Zero(), e2 = V::Zero();
  double q[6] = {};  // u^2, uv, v^2, u, v, 1 (all zero: the plane)
  bool curved = false;
  // Signed distance of x from the side along m (for a quadric: its height
  // above the surface, not the Euclidean distance; near enough within the
  // 32 points' neighbourhood, where the surface is a gentle height field).
  double offset(const V& x) const {
    const V d = x - c;
    if (!curved) return d.dot(m);
    const double u = d.dot(e1), v = d.dot(e2);
    return d.dot(m) - (q[0] * u * u + q[1] * u * v + q[2] * v * v + q[3] * u + q[4] * v + q[5]);
  }
};

void set_plane(Side& s, const PointPlane& f) {
  s.c = V(f.point[0], f.point[1], f.point[2]), s.m = V(f.normal[0], f.normal[1], f.normal[2]);
  s.curved = false;
  std::fill(std::begin(s.q), std::end(s.q), 0.0);
}

// A side whose plane leaves its points farther than this (over the
// neighbourhood's radius, RMS) is tried as a quadric.  Under it a plane
// does (the cube's and roof's faces: RMS 0 on exact samples).  Measured
// (crease_bench, three seeds, level 3): from 0.01 the cylinder's worst
// Hausdorff rose 0.96 -> 1.08% (its rim), from 0.02 not; the anchor's error
// falls 25% either way.
constexpr double kCurvedFrom = 0.02;
// A quadric side: at least this many points (6 terms and some to spare),
// its points within this RMS of it (over the radius; a faceted true mesh's
// cylinder of radius 0.03 leaves about 0.005), and no narrower than this.
constexpr size_t kCurvedPoints = 10;
constexpr double kCurvedFit = 0.02, kCurvedWidth = 0.15;
// Three planes win over two sides with a quadric when their squared
// distances sum to at most this share of the quadric fit's.
constexpr double kCornerOverCurve = 0.25;

// The quadric over the side's plane through `count` points; false when
// ill-posed (the points on a line or a conic of the plane) or not close.
bool fit_curved(const PointCloud& pc, const uint32_t* idx, size_t count, double radius, Side& s) {
  if (count < kCurvedPoints) return false;
  s.e1 = s.m.unitOrthogonal(), s.e2 = s.m.cross(s.e1);
  Eigen::MatrixXd a(count, 6);
  Eigen::VectorXd b(count);
  for (size_t j = 0; j < count; ++j) {
    const V d = V(pc.xyz[3 * size_t{idx[j]}], pc.xyz[3 * size_t{idx[j]} + 1], pc.xyz[3 * size_t{idx[j]} + 2]) - s.c;
    // Scaled by the radius so that the rank test is about the points' layout, not the model's units.
    const double u = d.dot(s.e1) / radius, v = d.dot(s.e2) / radius;
    a.row(static_cast<Eigen::Index>(j)) << u * u, u * v, v * v, u, v, 1;
    b[static_cast<Eigen::Index>(j)] = d.dot(s.m) / radius;
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  qr.setThreshold(1e-3);
  if (qr.rank() < 6) return false;
  const Eigen::VectorXd x = qr.solve(b);
  const double rms = std::sqrt((a * x - b).squaredNorm() / static_cast<double>(count));
  if (!(rms <= kCurvedFit)) return false;
  s.q[0] = x[0] / radius, s.q[1] = x[1] / radius, s.q[2] = x[2] / radius, s.q[3] = x[3], s.q[4] = x[4], s.q[5] = x[5] * radius;
  s.curved = true;
  return true;
}

// The sides' surfaces of `count` sides (2 or 3), starting from the seed
// planes: each point on the nearest side, the sides refitted until no point
// changes side.  False when a side has too few points, is not flat (nor,
// with two sides, a close quadric), is a strip rather than a patch, or two
// sides meet at less than the angle.  A corner's three sides are planes
// only: three curved sides over 32 points fit too much.
bool fit_sides(const PointCloud& pc, const uint32_t* idx, size_t found, double radius, const PointSides& sides, int count,
               bool curved_ok, Side* side_of, double& sse) {
  std::vector<uint32_t> group[3];
  uint8_t side[kWedgePoints];
  PointPlane fit[3];
  for (int round = 0; round < kWedgeRounds; ++round) {
    for (int k = 0; k < count; ++k) group[k].clear();
    bool moved = false;
    for (size_t j = 0; j < found; ++j) {
      const V x(pc.xyz[3 * size_t{idx[j]}], pc.xyz[3 * size_t{idx[j]} + 1], pc.xyz[3 * size_t{idx[j]} + 2]);
      int best = 0;
      for (int k = 1; k < count; ++k)
        if (std::abs(side_of[k].offset(x)) < std::abs(side_of[best].offset(x))) best = k;
      moved |= round == 0 || side[j] != best;
      side[j] = static_cast<uint8_t>(best);
      group[best].push_back(idx[j]);
    }
    if (!moved) break;
    for (int k = 0; k < count; ++k) {
      if (group[k].size() < kSidePoints) return false;
      fit[k] = fit_plane(pc, group[k].data(), group[k].size());
      set_plane(side_of[k], fit[k]);
      const double rms = std::sqrt(std::max(0.0, fit[k].variance[0])), width = std::sqrt(std::max(0.0, fit[k].variance[1]));
      if (curved_ok && rms > kCurvedFrom * radius && width >= kCurvedWidth * radius)
        fit_curved(pc, group[k].data(), group[k].size(), radius, side_of[k]);
    }
  }
  for (int k = 0; k < count; ++k) {
    // Flat sides, each a patch (not the strip of points along the line),
    // or a narrower strip whose points leave its plane no room to tilt
    // about it (a corner's third side beside the sample: the cube's
    // level 3, 4 points within 0.003 of one line).  A curved side passed
    // its own test when it was fitted.
    const double rms = std::sqrt(std::max(0.0, fit[k].variance[0])), width = std::sqrt(std::max(0.0, fit[k].variance[1]));
    if (!side_of[k].curved) {
      if (rms > 0.05 * radius) return false;
      if (width < 0.1 * radius && (width < kStripWidth * radius || rms > kStripTilt * width)) return false;
    }
    for (int o = 0; o < k; ++o)
      if (std::abs(side_of[k].m.dot(side_of[o].m)) >= sides.min_cos) return false;
  }
  sse = 0;
  for (size_t j = 0; j < found; ++j) {
    const V x(pc.xyz[3 * size_t{idx[j]}], pc.xyz[3 * size_t{idx[j]} + 1], pc.xyz[3 * size_t{idx[j]} + 2]);
    double d = std::abs(side_of[0].offset(x));
    for (int k = 1; k < count; ++k) d = std::min(d, std::abs(side_of[k].offset(x)));
    sse += d * d;
  }
  return true;
}

// Where the line p + t n meets side s nearest p (the smaller |t|), when it
// crosses it at more than a grazing angle; false when it misses.
bool side_hit(const Side& s, const V& p, const V& n, double& t) {
  if (!s.curved) {
    const double nm = n.dot(s.m);
    if (std::abs(nm) < 0.2) return false;  // the line runs along this side
    t = (s.c - p).dot(s.m) / nm;
    return true;
  }
  const V d = p - s.c;
  const double pu = d.dot(s.e1), pv = d.dot(s.e2), pw = d.dot(s.m);
  const double nu = n.dot(s.e1), nv = n.dot(s.e2), nw = n.dot(s.m);
  const double* q = s.q;
  // w(t) - Q(u(t), v(t)) = 0 as a2 t^2 + a1 t + a0 = 0.
  const double a2 = -(q[0] * nu * nu + q[1] * nu * nv + q[2] * nv * nv);
  const double a1 = nw - (2 * q[0] * pu * nu + q[1] * (pu * nv + pv * nu) + 2 * q[2] * pv * nv + q[3] * nu + q[4] * nv);
  const double a0 = pw - (q[0] * pu * pu + q[1] * pu * pv + q[2] * pv * pv + q[3] * pu + q[4] * pv + q[5]);
  if (std::abs(a2) * std::abs(a0) <= 1e-12 * a1 * a1) {
    if (a1 == 0) return false;
    t = -a0 / a1;
  } else {
    const double disc = a1 * a1 - 4 * a2 * a0;
    if (disc < 0) return false;
    // The root of smaller magnitude, without cancellation.
    const double r = -0.5 * (a1 + std::copysign(std::sqrt(disc), a1));
    if (r == 0) return false;
    t = a0 / r;
    if (a2 != 0 && std::abs(r / a2) < std::abs(t)) t = r / a2;
  }
  // Grazing test against the surface's normal at the hit, as for a plane.
  const double u = pu + t * nu, v = pv + t * nv;
  const double qu = 2 * q[0] * u + q[1] * v + q[3], qv = q[1] * u + 2 * q[2] * v + q[4];
  return std::abs(nw - qu * nu - qv * nv) >= 0.2 * std::sqrt(1 + qu * qu + qv * qv);
}

bool wedge_hit(const PointIndex& index, const double pd[3], const double nd[3], const PointSides& sides, double& t_out) {
  const PointCloud& pc = index.points();
  const float q[3] = {static_cast<float>(pd[0]), static_cast<float>(pd[1]), static_cast<float>(pd[2])};
  uint32_t idx[kWedgePoints];
  float dist2[kWedgePoints];
  const size_t found = index.nearest_k(q, kWedgePoints, idx, dist2);
  if (found < kWedgePoints) return false;
  const double radius = std::sqrt(double{dist2[found - 1]});
  const auto normal = [&](size_t j) {
    const float* m = sides.normals->data() + 3 * size_t{idx[j]};
    return V(m[0], m[1], m[2]);
  };
  const auto point = [&](size_t j) { return V(pc.xyz[3 * size_t{idx[j]}], pc.xyz[3 * size_t{idx[j]} + 1], pc.xyz[3 * size_t{idx[j]} + 2]); };
  // Seed planes: through a point with its normal, the one most points lie
  // on (within kSeedBand of the radius), then the one most of the others
  // lie on among those over the angle from it, and so on.  Not by the
  // normals alone: the normals of points within a spacing or two of the
  // feature blend the sides (the cube: (0.32, -0.42, 0.85) beside the
  // edge x = y = 1), and sides grown from such a seed split one face in two
  // or leave a corner's third face with too few points (the cube's level 3:
  // 2.3k odd vertices near lines fell back to the nearest point, 1-8e-4 of
  // the diagonal off).
  const double band = kSeedBand * radius;
  Side s[3];
  bool taken[kWedgePoints] = {};
  const auto seed = [&](int k) {
    int best = -1, best_support = 0;
    for (size_t j = 0; j < found; ++j) {
      const V nj = normal(j);
      bool far = true;
      for (int o = 0; o < k; ++o) far &= std::abs(nj.dot(s[o].m)) < sides.min_cos;
      if (!far) continue;
      int support = 0;
      for (size_t i = 0; i < found; ++i) support += !taken[i] && std::abs((point(i) - point(j)).dot(nj)) <= band;
      if (support > best_support) best_support = support, best = static_cast<int>(j);
    }
    if (best < 0 || best_support < static_cast<int>(kSidePoints)) return false;
    s[k] = Side{};
    s[k].c = point(static_cast<size_t>(best)), s[k].m = normal(static_cast<size_t>(best));
    for (size_t i = 0; i < found; ++i) taken[i] |= std::abs((point(i) - s[k].c).dot(s[k].m)) <= band;
    return true;
  };
  if (!seed(0) || !seed(1)) return false;  // one sheet here
  int count = 2;
  const Side s1[2] = {s[0], s[1]};
  const auto three_planes = [&](Side* s3, double& sse3) {
    s[0] = s1[0], s[1] = s1[1];
    if (!seed(2)) return false;
    s3[0] = s1[0], s3[1] = s1[1], s3[2] = s[2];
    return fit_sides(pc, idx, found, radius, sides, 3, false, s3, sse3);
  };
  double sse = 0;
  {
    // Two sides, either of them a quadric where its plane leaves its points
    // (a flat face beside a curved wall).  Where a side is curved, or two
    // sides do not fit, three planes (a corner) are tried as well, and taken
    // when they fit and (against a curved fit) leave the points a quarter of
    // its squared distances or less: a curved wall cut into two planes
    // passes the corner's test where the wall turns little over the
    // neighbourhood, with the line's hit on a chord (a cylinder of radius
    // 0.03 beside its cap: 3e-4 off with three planes taken whenever they
    // were closer at all, 2e-6 with the quadric), while a corner's two faces
    // under one quadric pass the curved test where the third face shows a
    // few points only (the cube's corners: three planes fit exactly).
    const bool two = fit_sides(pc, idx, found, radius, sides, 2, true, s, sse);
    const bool curved = two && (s[0].curved || s[1].curved);
    if (!two || curved) {
      const Side s2[2] = {s[0], s[1]};
      Side s3[3];
      double sse3 = 0;
      const bool three = three_planes(s3, sse3);
      if (three && (!two || sse3 <= kCornerOverCurve * sse)) {
        std::copy(s3, s3 + 3, s);
        count = 3;
      } else if (two) {
        s[0] = s2[0], s[1] = s2[1];
      } else {
        // Two planes without the quadric (its fit moved the points' sides and then failed).
        s[0] = s1[0], s[1] = s1[1];
        if (!fit_sides(pc, idx, found, radius, sides, 2, false, s, sse)) return false;
      }
    }
  }
  const V p(pd[0], pd[1], pd[2]), n(nd[0], nd[1], nd[2]);
  bool hit = false;
  for (int k = 0; k < count; ++k) {
    double t = 0;
    if (!side_hit(s[k], p, n, t)) continue;
    const V x = p + t * n;
    // A quadric only near its own points: it may turn anywhere beyond them.
    if (s[k].curved && (x - s[k].c).norm() > radius) continue;
    // On this side's part: on the same side of every other side as this
    // side's points, or beyond it by kInsideSlack at most.  A vertex on
    // the feature line itself hits its own side there, where rounding puts
    // it a hair beyond the other side's plane: without the band no side
    // took it when its line ran along the other side (the roof's level 1,
    // seed 3: 5 crease vertices on the box's edges fell back to the nearest
    // point, 0.004-0.02 off).
    bool inside = true;
    for (int o = 0; o < count; ++o) {
      const double here = s[o].offset(x);
      if (o != k && here * s[o].offset(s[k].c) < 0 && std::abs(here) > kInsideSlack * radius) inside = false;
    }
    if (!inside) continue;
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
                           double half_length, SampleScratch& scratch, bool fit, const PointSides* sides, bool widen,
                           bool tight) {
  const PointCloud& pc = index.points();
  const V p(pd[0], pd[1], pd[2]), n(nd[0], nd[1], nd[2]);
  const auto point = [&](uint32_t i) { return V(pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]); };
  Sample out;
  // Points inside the cylinder: horizontal distance to the line under
  // `radius`, vertical offset along it under `half_length`.
  std::vector<uint32_t>& near = scratch.near;
  // The wedge's sides (next to a tagged line, within its gate).
  const PointSides* const original_sides = sides;
  // Whether the fit's own points (the kFitPoints nearest the foot) all
  // face the line's way (PointSides::agrees): then no crease, tagged or not,
  // is among them, and the sample is a clean cloud's, with its tight kernel
  // and facet hit (a file with any tag once lost both everywhere, on a
  // machined part's flat faces too).  Measured against a distance from the
  // tagged edges (bench/crease_bench.md, fourteenth session): that one
  // raised level 1 beside the features the tags miss (the anchor +6-13%).
  const auto clean_foot = [&](double d) {
    if (!original_sides) return true;
    if (!original_sides->clean_where_agreed) return false;
    const float f[3] = {static_cast<float>(pd[0] + d * nd[0]), static_cast<float>(pd[1] + d * nd[1]),
                        static_cast<float>(pd[2] + d * nd[2])};
    uint32_t idx[kFitPoints];
    float d2[kFitPoints];
    const size_t found = index.nearest_k(f, kFitPoints, idx, d2);
    for (size_t j = 0; j < found; ++j)
      if (!original_sides->agrees(idx[j], nd)) return false;
    return true;
  };
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
    // A clean cloud's fit (no `widen`, `tight`) with the tight kernel; one-sided
    // sampling beside creases keeps the narrow one (its wedge and sides are
    // tuned with it).
    if (fit) {
      const bool one_sided = !clean_foot(d);
      const SurfaceFit f = fit_height(index, pd, nd, d, kFitPoints, scratch.fit, one_sided ? sides : nullptr, widen,
                                      tight && !widen && !one_sided);
      if (f.ok && (std::abs(f.height) <= half_length || std::abs(d) > half_length))
        d = f.height, out.fitted = true, out.spread = f.spread;
      // A clean cloud on a flat facet: the facet, not the fit's rounding of
      // the bends beside it (facet_hit.h); elsewhere on a clean cloud the fit
      // made to pass through the points around the line (residual_hit.h).
      double t = 0;
      const bool clean = out.fitted && tight && !widen && !one_sided;
      if (clean && facet_hit(index, pd, nd, d, f.radius, t) && std::abs(t) <= half_length)
        d = t;
      else if (clean && residual_hit(index, pd, nd, f, t) && std::abs(t) <= half_length)
        d = t;
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
    // when a surface through both could pass (rising at most kSteep times,
    // kSteepOneSided when the candidates are one side's,
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
    const double steep = sides ? kSteepOneSided : kSteep;
    const auto on_sheet = [&](const Cand& c) {
      return std::abs(c.vertical - anchor.vertical) <= steep * (c.horizontal + anchor.horizontal);
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
