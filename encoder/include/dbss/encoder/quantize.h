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

// The nearest integer to distance / step (ties to even, the rounding mode's
// default), cut to the format's |q| <= kMaxAbsDisplacement.  The cut only
// bites with steps far below the geometry's scale.
inline Quantized quantize(double distance, float step) {
  const double q = std::nearbyint(distance / step);
  const double limit = format::kMaxAbsDisplacement;
  return {static_cast<int32_t>(std::clamp(q, -limit, limit)), std::abs(q) > limit};
}

}  // namespace dbss
