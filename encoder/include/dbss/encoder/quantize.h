// The displacement quantizer, one for every representation the encoder
// makes: dbss's levels and the full-vertex DSS baseline round the same way,
// so `dbss compare` measures the representations and not two quantizers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dbss/format/container.h"

namespace dbss {

// The step that keeps the rounding error of a displacement within `error`
// times the bounding-box diagonal: rounding to the nearest multiple of the
// step moves a vertex at most half a step.  Binary32, as the file stores it.
inline float quantization_step(double error, double diagonal) { return static_cast<float>(2 * error * diagonal); }

struct Quantized {
  int32_t q = 0;         // the stored integer: the vertex moves q * step along its normal
  bool clamped = false;  // |distance / step| passed the format's range and q was cut to it
};

// Past the points' density (a level with more samples than there are
// points), a displacement under this many steps is stored as 0: there the
// samples re-express the fitted surface between points, and their small
// values are the fit's wobble, not the shape.  Measured on four sampled
// shapes (30k points): levels past the density cost 1.5-2.2x fewer bytes
// for 1-5% more error against the true surface.  It was 1.5 until the
// levels after this one stored nothing (dead_zone_steps): their plain
// butterfly refinement then carries this level's rounding errors into a
// wavier limit surface, and with 1.5 steps a torus of 3,000 points came out
// 2.4% farther from the truth at level 5 than at level 4 (1.8% with 1.0);
// on the eight (30k points) 1.0 costs 16% more bytes at that level for 2%
// less error (bench/floor_probe).
inline constexpr double kDeadZoneSteps = 1.0;

// A displacement within this many of its fit's standard errors
// (Sample::spread) is stored as 0 at any level: what the points cannot tell
// from their noise.
inline constexpr double kSpreadDeadZone = 2.0;

// The dead zone, in steps, of a level with `samples` displacements refining
// a level of `coarser` vertices, from `points` points: plain rounding (0.5)
// up to the points' density; kDeadZoneSteps on the level that passes it;
// infinite (every q is 0: the level is the plain butterfly refinement of
// the one before) once the coarser level alone has more vertices than there
// are points.  There the fit has nothing left to add between the points:
// measured against the true surface on the rd_bench shapes (floor_probe),
// the samples of such levels differ from the surface by 3e-5..1e-4 of the
// diagonal (the fit's own error) while the surface's true displacements are
// under a step, so every q they store is the fit's error coded as detail,
// and the level came out farther from the truth than the one before.
inline double dead_zone_steps(size_t samples, size_t points, size_t coarser = 0) {
  if (coarser > points) return HUGE_VAL;
  return samples > points ? kDeadZoneSteps : 0.5;
}

// The nearest integer to distance / step (ties to even, the rounding mode's
// default), 0 when |distance| is under dead_zone steps, cut to the format's
// |q| <= kMaxAbsDisplacement.  The cut only bites with steps far below the
// geometry's scale.
inline Quantized quantize(double distance, float step, double dead_zone = 0.5) {
  if (std::abs(distance) < dead_zone * step) return {};
  const double q = std::nearbyint(distance / step);
  const double limit = format::kMaxAbsDisplacement;
  return {static_cast<int32_t>(std::clamp(q, -limit, limit)), std::abs(q) > limit};
}

}  // namespace dbss
