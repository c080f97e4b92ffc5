// Displacement sampling (paper, section 3.2): the signed distance from an
// odd vertex along its normal to the surface the points describe.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/encoder/point_index.h"
#include "dbss/encoder/surface_fit.h"

namespace dbss {

enum class SampleSource : uint8_t {
  triangle,  // the line hit a triangle of points inside the cylinder (the paper's method)
  plane,     // fallback: a least-squares plane through the cylinder's points
  nearest,   // fallback: the nearest point's offset along the normal
};

struct Sample {
  double distance = 0;  // along the unit normal, model units
  SampleSource source = SampleSource::nearest;  // what found the sheet the line meets
  bool fitted = false;   // distance is to the local surface fit (surface_fit.h) there
  bool clamped = false;  // |distance| was cut to the limit
  double spread = 0;     // the fit's standard error at the line when fitted (SurfaceFit::spread), else 0
  bool wedge = false;    // from the two sides' planes next to a crease (PointSides::wedge)
};

// Points in the local surface fit around the line's first hit: enough to
// average sampling noise away (a quadric has 6 terms), few enough to keep
// the fit local (about 2.7 point spacings across).  Measured on sampled
// shapes with noise of 5e-4 of the diagonal: 16 points leave level 3-5
// errors 10-15% higher, 40 points cost detail on the elephant.
inline constexpr size_t kFitPoints = 24;

// Working memory of sample_displacement(), owned by the caller so that a
// loop of samples allocates once: one per thread sampling at the same time.
// Nothing in it carries from one call to the next.
struct SampleScratch {
  struct Candidate {
    double horizontal, vertical;  // distance from the line, offset along it
    uint32_t point;               // index into the points
  };
  std::vector<uint32_t> near;          // points in the cylinder's bounding ball
  std::vector<Candidate> cylinder;     // those inside the cylinder
  FitScratch fit;                      // surface_fit.h
};

// p: the odd vertex; n: its unit normal (the decoder's); radius: the
// cylinder's horizontal threshold; half_length: its vertical threshold; the
// result is clamped to |distance| <= half_length.  The line's first hit (a
// triangle of points in the cylinder, their plane, or the nearest point)
// picks the sheet; the distance is then taken to the fitted surface of the
// kFitPoints points around that hit (fit_height), unless `fit` is false or
// the fit fails.  `sides` (may be null): one-sided, the hit and the fit
// from the points whose normal agrees with n (PointSides), unless fewer
// than 3 of them are in the cylinder.
// `widen`: fit_height's wider fit on noise (a cloud points_are_noisy);
// without it, without `sides` and with `tight` (a cloud points_are_quiet),
// fit_height's tight kernel (a clean cloud's fit keeps to the nearest
// points: bench/rd_bench.md, twelfth session).
Sample sample_displacement(const PointIndex& points, const double p[3], const double n[3], double radius,
                           double half_length, SampleScratch& scratch, bool fit = true, const PointSides* sides = nullptr,
                           bool widen = false, bool tight = true);
// The same with scratch space of its own (allocated per call): for single
// samples and tests.
Sample sample_displacement(const PointIndex& points, const double p[3], const double n[3], double radius,
                           double half_length, bool fit = true);

}  // namespace dbss
