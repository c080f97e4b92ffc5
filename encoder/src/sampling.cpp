#include "dbss/encoder/sampling.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace dbss {

namespace {
using V = Eigen::Vector3d;

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
  if (cyl.size() >= 3) {
    // Candidate triangles from the points nearest the line; the hit nearest
    // to the vertex wins, so the closest sheet of a thin part is taken.
    const size_t m = std::min<size_t>(cyl.size(), 7);
    std::partial_sort(cyl.begin(), cyl.begin() + m, cyl.end(),
                      [](const Cand& a, const Cand& b) { return a.horizontal < b.horizontal; });
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
    // Plane through the cylinder's points.
    V c = V::Zero();
    for (const Cand& x : cyl) c += point(x.point);
    c /= static_cast<double>(cyl.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Cand& x : cyl) cov += (point(x.point) - c) * (point(x.point) - c).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const V m3 = eig.eigenvectors().col(0);
    const double nm = n.dot(m3);
    if (std::abs(nm) > 0.3) return finish((c - p).dot(m3) / nm, SampleSource::plane);
  }
  // Nearest point's offset along the normal.
  const uint32_t i = index.nearest(q);
  const V x(pc.xyz[3 * i], pc.xyz[3 * i + 1], pc.xyz[3 * i + 2]);
  return finish((x - p).dot(n), SampleSource::nearest);
}

}  // namespace dbss
