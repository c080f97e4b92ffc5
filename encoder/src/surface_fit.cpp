#include "dbss/encoder/surface_fit.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace dbss {

namespace {

// Weighted least squares of h over (1, u, v[, u², uv, v²]); returns the
// coefficients (6, the last three zero for a plane) and whether they are
// finite.
bool solve(const FitScratch& s, bool quadric, Eigen::Matrix<double, 6, 1>& c) {
  Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
  for (size_t i = 0; i < s.h.size(); ++i) {
    if (s.w[i] == 0) continue;
    const Eigen::Matrix<double, 6, 1> x(1, s.u[i], s.v[i], s.u[i] * s.u[i], s.u[i] * s.v[i], s.v[i] * s.v[i]);
    a += s.w[i] * x * x.transpose();
    b += s.w[i] * s.h[i] * x;
  }
  c.setZero();
  if (quadric) {
    c = a.ldlt().solve(b);
  } else {
    c.head<3>() = a.topLeftCorner<3, 3>().ldlt().solve(b.head<3>());
  }
  return c.allFinite();
}

double residual(const FitScratch& s, size_t i, const Eigen::Matrix<double, 6, 1>& c) {
  const double u = s.u[i], v = s.v[i];
  return s.h[i] - (c[0] + c[1] * u + c[2] * v + c[3] * u * u + c[4] * u * v + c[5] * v * v);
}

// The kernels over the distance r from the line, in units of the
// neighbourhood's radius.  Narrow: (1 - r^2)^2, zero at the radius, so a
// point entering or leaving the k nearest moves the fit continuously and
// the fit stays close to the points it interpolates (measured against the
// true surface on the rd_bench shapes without noise: samples 20-35% closer
// than the wide kernel, the levels' floor 10-15% lower).  Wide: a Gaussian
// of sigma radius / sqrt(2), which averages about twice as many points
// (noise of 1e-3 of the diagonal: the narrow kernel alone left level 3 3%
// farther from the truth).
//
// Tight: (1 - r^2)^4, for clean clouds (fit_height's `tight`).  Half the
// narrow kernel's width at half weight (0.42 of the radius against 0.54),
// so a bend of the surface inside the neighbourhood is rounded over less of
// it.  Measured with bench/floor_probe --regions (30k points, no noise):
// the true meshes bend at their edges (the eight's facets meet at 15-33
// degrees), advancing front through the points is exact beyond a spacing
// from those edges, and the narrow fit's level surface was not: 1-4
// spacings from them it added 27e-6 of the eight's 112e-6 (advancing front
// 2e-6).  With the tight kernel the finest level comes 4-10% closer on all
// five rd_bench shapes (bench/rd_bench.md, twelfth session).
enum class Kernel { narrow, wide, tight };
double kernel_weight(Kernel k, double u, double v) {
  const double r2 = u * u + v * v;
  if (k == Kernel::wide) return std::exp(-2 * r2);
  if (r2 >= 1) return 0;
  const double w = (1 - r2) * (1 - r2);
  return k == Kernel::tight ? w * w : w;
}

// The scatter (RMS residual over the radius) below which the points are
// taken as noise-free; from twice it, as noise.  Without noise, the points
// of the rd_bench shapes scatter about a quadric by under 1% of the radius
// (the shape's own detail); noise of 1e-3 of the diagonal gives 5-10%.
constexpr double kQuietScatter = 0.02;

// points_are_noisy's neighbourhood: the fit's own (kFitPoints, sampling.h).
constexpr size_t kNoiseProbePoints = 24;

// points_are_quiet: the tight kernel only where the median ratio of the
// 12-point fit's scatter to the 24-point fit's is under this.  Measured
// (rd_bench, 30k points, seed 1; ratio, then the finest level tight against
// narrow): no noise 0.29-0.33 (tight 4-10% closer); armadillo at noise 1e-4
// of the diagonal 0.38 (-8.4%), elephant 1e-4 0.48 (-5.2%), eight 1e-4 0.51
// (-5.2%); elephant 2e-4 0.56 (+2.5%: tight lost).  See bench/rd_bench.md,
// twelfth session (h12-mild).
constexpr double kShapeScatterRatio = 0.54;

// A fit whose points scatter under this fraction of its radius is exact
// (a plane, float rounding): its ratio says nothing of noise.
constexpr double kExactScatter = 1e-4;

// A wider neighbourhood's fit is taken on noise when its height and the
// first fit's lie within this many of their standard errors (summed) of
// each other: their confidence intervals overlap.  Measured on noisy
// clouds (1e-3 of the diagonal, 30k points): 1 kept too little (the rise
// past level 3 stayed 2.5%), 2 keeps the armadillo's level 3 within 3% of
// the narrow fit's.
constexpr double kWiderAgreement = 2.0;

struct Fitted {
  double height = 0, residual = 0;
  Eigen::Matrix<double, 6, 1> c = Eigen::Matrix<double, 6, 1>::Zero();
  double spread = 0;  // the standard error of height: residual * sqrt(sum w^2) / sum w
};

// The weighted fit with `kernel`, then two rounds of robust reweighting.
bool fit_weighted(FitScratch& s, bool quadric, Kernel kernel, double radius, Fitted& out) {
  const size_t used = s.h.size();
  s.gauss.resize(used);
  for (size_t i = 0; i < used; ++i) s.gauss[i] = kernel_weight(kernel, s.u[i], s.v[i]);
  s.w = s.gauss;
  Eigen::Matrix<double, 6, 1> c;
  if (!solve(s, quadric, c)) return false;
  for (int round = 0; round < 2; ++round) {
    // Robust scale: the median absolute residual; points beyond 4.685 of it
    // (Tukey's constant for 95% efficiency on Gaussian noise) get no weight.
    s.residual.resize(used);
    for (size_t i = 0; i < used; ++i) s.residual[i] = std::abs(residual(s, i, c));
    s.sorted = s.residual;
    std::nth_element(s.sorted.begin(), s.sorted.begin() + used / 2, s.sorted.end());
    const double scale = 1.4826 * s.sorted[used / 2];
    if (!(scale > 1e-12 * radius)) break;  // exact fit: nothing to reweight
    for (size_t i = 0; i < used; ++i) {
      const double x = s.residual[i] / (4.685 * scale);
      s.w[i] = x < 1 ? s.gauss[i] * (1 - x * x) * (1 - x * x) : 0;
    }
    Eigen::Matrix<double, 6, 1> next;
    if (!solve(s, quadric, next)) break;
    c = next;
  }
  double sw = 0, sww = 0, swr = 0;
  for (size_t i = 0; i < used; ++i) sw += s.w[i], sww += s.w[i] * s.w[i], swr += s.w[i] * std::pow(residual(s, i, c), 2.0);
  out.height = c[0];
  out.c = c;
  out.residual = sw > 0 ? std::sqrt(swr / sw) : 0;
  out.spread = sw > 0 ? out.residual * std::sqrt(sww) / sw : 0;
  return std::isfinite(out.height);
}

}  // namespace

namespace {

// The k points nearest the foot p + t0 n in the line's frame (u, v in
// units of the neighbourhood's radius, h along n from p), less those
// farther from t0 along n than half the radius; the radius, or 0 when
// there are too few.
double gather(const PointIndex& index, const double p[3], const double n[3], double t0, size_t k, FitScratch& s,
              const PointSides* sides) {
  const PointCloud& pc = index.points();
  const float foot[3] = {static_cast<float>(p[0] + t0 * n[0]), static_cast<float>(p[1] + t0 * n[1]),
                         static_cast<float>(p[2] + t0 * n[2])};
  s.index.resize(k);
  s.dist2.resize(k);
  const size_t found = index.nearest_k(foot, k, s.index.data(), s.dist2.data());
  if (found < 4) return 0;
  const double radius = std::sqrt(static_cast<double>(s.dist2[found - 1]));
  if (!(radius > 0)) return 0;
  // A frame with n as its third axis.
  const Eigen::Vector3d nz(n[0], n[1], n[2]);
  double f1[3], f2[3];
  fit_frame(n, f1, f2);
  const Eigen::Vector3d e1(f1[0], f1[1], f1[2]), e2(f2[0], f2[1], f2[2]);
  const Eigen::Vector3d origin(p[0], p[1], p[2]);
  // Points farther than this from the first estimate along n belong to
  // another sheet (a thin part's other side) or are outliers.
  const double band = 0.5 * radius;
  s.u.clear(), s.v.clear(), s.h.clear();
  for (size_t i = 0; i < found; ++i) {
    const uint32_t j = s.index[i];
    if (sides && !sides->agrees(j, n)) continue;
    const Eigen::Vector3d d = Eigen::Vector3d(pc.xyz[3 * j], pc.xyz[3 * j + 1], pc.xyz[3 * j + 2]) - origin;
    const double h = d.dot(nz);
    if (std::abs(h - t0) > band) continue;
    // Coordinates in units of the radius keep the normal equations well
    // conditioned at every level.
    const double u = d.dot(e1) / radius, v = d.dot(e2) / radius;
    s.u.push_back(u), s.v.push_back(v), s.h.push_back(h);
  }
  return s.h.size() < 4 ? 0 : radius;
}

}  // namespace

void fit_frame(const double n[3], double e1[3], double e2[3]) {
  const Eigen::Vector3d nz(n[0], n[1], n[2]);
  const Eigen::Vector3d helper = std::abs(nz.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d a = nz.cross(helper).normalized(), b = nz.cross(a);
  for (int k = 0; k < 3; ++k) e1[k] = a[k], e2[k] = b[k];
}

SurfaceFit fit_height(const PointIndex& index, const double p[3], const double n[3], double t0, size_t k,
                      FitScratch& s, const PointSides* sides, bool widen, bool tight) {
  SurfaceFit out;
  const double radius = gather(index, p, n, t0, k, s, sides);
  if (!(radius > 0)) return out;
  const double band = 0.5 * radius;
  size_t used = s.h.size();
  // The quadric where the points are enough to pin its curvature terms.
  bool quadric = used >= 12;
  Fitted narrow;
  if (!fit_weighted(s, quadric, tight ? Kernel::tight : Kernel::narrow, radius, narrow)) return out;
  double height = narrow.height, spread = narrow.residual, error = narrow.spread;
  // Points scattered about the narrow fit by more than kQuietScatter of the
  // radius are noise, not shape: the wide kernel averages more of them.
  // Between the two thresholds the heights are blended, so neighbouring
  // samples on either side of a threshold do not jump apart.
  const double blend = std::clamp((narrow.residual / radius - kQuietScatter) / kQuietScatter, 0.0, 1.0);
  if (blend > 0) {
    Fitted wide;
    if (fit_weighted(s, quadric, Kernel::wide, radius, wide)) {
      // On noise, twice the points where the shape allows it: a height
      // within kWiderAgreement standard errors (each fit's own, summed) of
      // the first one's is the same surface, seen with half the variance.
      // Why: the levels' vertices keep the fit's noise, and once the levels
      // store only zeros the butterfly turns high-frequency vertex noise
      // into a wavier surface (noise of 1e-3 of the diagonal: eight and
      // knot1 rose 2.1-2.4% from level 3 to 4).  With the wider fit the
      // neighbouring vertices share more of their points, their errors
      // move together and the rise is 1.4-1.7%.  Unconditionally, four
      // times the points cost the armadillo's detail (level 3 37% farther
      // from the truth), so the agreement test guards the shape.
      const double r = widen ? gather(index, p, n, t0, 2 * k, s, sides) : 0;
      Fitted wider;
      if (r > 0 && fit_weighted(s, s.h.size() >= 12, Kernel::wide, r, wider) &&
          std::abs(wider.height - wide.height) <= kWiderAgreement * (wide.spread + wider.spread)) {
        wide = wider;
        used = s.h.size();
      }
      height = (1 - blend) * narrow.height + blend * wide.height;
      spread = (1 - blend) * narrow.residual + blend * wide.residual;
      error = (1 - blend) * narrow.spread + blend * wide.spread;
    }
  }
  // An ill-posed quadric (points along a line) can put its value at the
  // line far from every point.
  if (!std::isfinite(height) || std::abs(height - t0) > band) return out;
  out.ok = true;
  out.height = height;
  out.residual = spread;
  out.spread = error;
  out.points = static_cast<uint32_t>(used);
  out.radius = radius;
  for (int k = 0; k < 6; ++k) out.coef[k] = narrow.c[k];
  out.blend = blend;
  return out;
}

namespace {

// The plane normal of the kNoiseProbePoints nearest x; false with under 6.
bool probe_normal(const PointIndex& index, const float* x, std::vector<uint32_t>& near, std::vector<float>& dist2,
                  Eigen::Vector3d& normal) {
  const PointCloud& pc = index.points();
  const size_t found = index.nearest_k(x, kNoiseProbePoints, near.data(), dist2.data());
  if (found < 6) return false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (size_t a = 0; a < found; ++a) c += Eigen::Vector3d(pc.xyz[3 * near[a]], pc.xyz[3 * near[a] + 1], pc.xyz[3 * near[a] + 2]);
  c /= static_cast<double>(found);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t a = 0; a < found; ++a) {
    const Eigen::Vector3d d = Eigen::Vector3d(pc.xyz[3 * near[a]], pc.xyz[3 * near[a] + 1], pc.xyz[3 * near[a] + 2]) - c;
    cov += d * d.transpose();
  }
  normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0);
  return true;
}

// Each of up to 1,024 points spread evenly through the cloud, with the
// plane normal of its kNoiseProbePoints nearest and the fit of those points
// along it (fit_height): `look(p, n, fit)` for every probe whose fit is ok.
template <class Look>
void walk_probes(const PointIndex& index, FitScratch& s, Look&& look) {
  const PointCloud& pc = index.points();
  const size_t n = pc.size(), m = std::min<size_t>(n, 1024);
  std::vector<uint32_t> near(kNoiseProbePoints);
  std::vector<float> dist2(kNoiseProbePoints);
  for (size_t j = 0; j < m; ++j) {
    const size_t i = j * n / m;
    const float* x = &pc.xyz[3 * i];
    Eigen::Vector3d normal;
    if (!probe_normal(index, x, near, dist2, normal)) continue;
    const double p[3] = {x[0], x[1], x[2]}, nn[3] = {normal.x(), normal.y(), normal.z()};
    const SurfaceFit all = fit_height(index, p, nn, 0, kNoiseProbePoints, s);
    if (all.ok && all.radius > 0) look(p, nn, all);
  }
}

// The median of `v` (reordered); 0 when empty.
double median(std::vector<double>& v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

// One walk over the probes for all three figures (each was a walk of its
// own, and encode_levels asked for them again on every control candidate).
// The scatter: the RMS residual of each probe's fit, over its radius
// (noisy) and in model units (noise).  The ratio (quiet): of the fit to
// the 12 nearest points over that to the 24 nearest.  A quadric's leftover
// from the shape grows with the neighbourhood's radius cubed, so halving
// the points (radius / sqrt 2) leaves about a third of it (rd_bench shapes
// without noise: 0.29-0.33); noise stays (with the dropped degrees of
// freedom, about 0.6).  Fits with a scatter under kExactScatter of the
// radius (planes, float rounding) count as shape.
PointNoise point_noise(const PointIndex& index) {
  FitScratch s;
  std::vector<double> relative, absolute, ratio;
  walk_probes(index, s, [&](const double p[3], const double n[3], const SurfaceFit& all) {
    relative.push_back(all.residual / all.radius);
    absolute.push_back(all.residual);
    if (all.residual < kExactScatter * all.radius) {
      ratio.push_back(0);
      return;
    }
    const SurfaceFit half = fit_height(index, p, n, 0, kNoiseProbePoints / 2, s);
    if (half.ok) ratio.push_back(half.residual / all.residual);
  });
  PointNoise out;
  out.noisy = median(relative) > kQuietScatter;
  out.quiet = median(ratio) < kShapeScatterRatio;
  out.noise = median(absolute);
  return out;
}

bool points_are_quiet(const PointIndex& index) { return point_noise(index).quiet; }

bool points_are_noisy(const PointIndex& index) { return point_noise(index).noisy; }

double points_noise(const PointIndex& index) { return point_noise(index).noise; }

}  // namespace dbss
