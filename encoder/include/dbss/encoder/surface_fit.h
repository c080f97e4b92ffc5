// The surface the points describe near an odd vertex's normal line, as a
// weighted least-squares height field over the line's foot: what the
// displacement is sampled against, so that sampling noise (which of a few
// nearby points or triangles the line happens to hit) becomes a smooth
// surface instead of noise coded at full precision (issue 15).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dbss/encoder/point_index.h"

namespace dbss {

class CreaseLines;

struct FitScratch {
  std::vector<uint32_t> index;
  std::vector<float> dist2;
  std::vector<double> u, v, h, w;  // the kept points in the line's frame, their weights
  std::vector<double> gauss, residual, sorted;  // the robust rounds' working arrays
};

// One-sided sampling next to a crease: a unit normal per point (3 floats
// each) and the cosine under which a point's normal disagrees with the
// sample's line; such points (the other side of a crease, or the blend
// along it) are left out, so the fit does not round the feature.
struct PointSides {
  const std::vector<float>* normals = nullptr;
  double min_cos = 0;
  // Next to a feature, the line's hit on the two sides' planes (sampling.cpp).
  bool wedge = true;
  // The wedge only within reach of these tagged crease edges; null: anywhere.
  const CreaseLines* lines = nullptr;
  // A sample whose fit's points all agree is a clean cloud's: the fit over
  // all the points with the tight kernel, and the facet hit (sampling.cpp).
  // False: every sample one-sided, with the narrow kernel.
  bool clean_where_agreed = false;
  bool agrees(uint32_t i, const double n[3]) const {
    const float* m = normals->data() + 3 * size_t{i};
    return std::abs(m[0] * n[0] + m[1] * n[1] + m[2] * n[2]) >= min_cos;
  }
};

struct SurfaceFit {
  bool ok = false;
  double height = 0;    // where the line meets the fitted surface, along n from p
  double residual = 0;  // weighted RMS distance of the points from the fit: their noise (model units)
  uint32_t points = 0;  // points the fit used
  double radius = 0;    // the neighbourhood's radius (model units)
  double spread = 0;    // standard error of `height` from the points' scatter (model units): how far the fit itself may be off
  // The first (narrow or tight) fit's height field in the line's frame
  // (fit_frame): h = c0 + c1 u + c2 v + c3 u^2 + c4 uv + c5 v^2, u and v in
  // units of `radius`; `blend` is the share of the wide fit in `height`
  // (0 on clean clouds), when the field is not the whole of it.
  double coef[6] = {};
  double blend = 0;
};

// The frame fit_height uses for the line along the unit n: e1, e2 normal to it.
void fit_frame(const double n[3], double e1[3], double e2[3]);

// p: the odd vertex; n: its unit normal; t0: a first estimate of the
// surface along the line (the sampler's hit, which picks the sheet of a thin
// part).  The `k` points nearest the foot p + t0 n, less those farther from
// the estimate along n than half the neighbourhood's radius (another sheet),
// are fitted by a quadric height field over the plane normal to n (a plane
// with fewer than 12 points), weighted by their distance from the line: a
// kernel that vanishes at the neighbourhood's radius, so the fit follows the
// points closely and moves continuously from one line to the next; where
// the points scatter about that fit like noise (RMS over 2% of the radius),
// blended into a wider Gaussian that averages more of them.  The
// neighbourhood follows the local point spacing, whatever the level's edge
// length.  Two more rounds reweight each point by its residual (Tukey's
// biweight), so a stray point left among the surface's points does not pull
// the fit.  Not ok with fewer than 4 points or an ill-posed fit.
// `sides` (may be null): only the points whose normal agrees with n.
// `widen`: where the points scatter like noise, also try twice the points
// and keep that fit when it agrees with the first (points_are_noisy says
// when to ask for it).  `tight`: the first fit's kernel twice as steep
// ((1 - r^2)^4 over the neighbourhood's radius, not (1 - r^2)^2), for clean
// clouds, where there is no noise to average and a wide kernel only rounds
// the surface's bends.
SurfaceFit fit_height(const PointIndex& points, const double p[3], const double n[3], double t0, size_t k,
                      FitScratch& scratch, const PointSides* sides = nullptr, bool widen = false, bool tight = false);

// True when the cloud as a whole scatters like noise about its local
// surface: the median, over up to 1,024 points spread evenly through it, of
// the RMS scatter of their 24 nearest points about a quadric fit, over the
// neighbourhood's radius, is above 2% (the level where fit_height starts to
// blend in its wide kernel).  Sampled clouds of the rd_bench shapes: under
// 1% clean, 2.5-10% with noise of 5e-4..2e-3 of the diagonal.
bool points_are_noisy(const PointIndex& points);

// True when the scatter the fits see is the shape's rather than noise's:
// the median, over the same probe points, of the RMS scatter about the fit
// to the 12 nearest points over that about the fit to the 24 nearest is
// under 0.54 (a shape's leftover falls about threefold with the halved
// neighbourhood, noise's does not).  Without it the tight kernel averages
// too few noisy points (elephant, noise 2e-4 of the diagonal: the finest
// level 2.5% farther from the truth than with the narrow kernel).
bool points_are_quiet(const PointIndex& points);

// The same fits' median RMS scatter in model units: on a noisy cloud, about
// the noise's standard deviation along the surface's normal.
double points_noise(const PointIndex& points);

// The three figures above from one walk over the probe points, for a
// caller that needs more than one (an encoding asks for them once and
// passes them down: encode_levels).
struct PointNoise {
  bool noisy = false;  // points_are_noisy
  bool quiet = true;   // points_are_quiet
  double noise = 0;    // points_noise
};
PointNoise point_noise(const PointIndex& points);

}  // namespace dbss
