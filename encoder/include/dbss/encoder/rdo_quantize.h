// Rate-distortion optimised quantization of one level's displacements for
// LEVL coding 2 (spec/dbss-format.md section 9b): each odd vertex keeps its
// rounded integer or takes the one a step nearer zero, whichever lowers
// (error)^2 + lambda * bits over the whole level.  The error is the
// displacement's own, in steps; the bits are those of coding 2's context
// model with its probabilities estimated from the level itself (static
// counts, not the coder's adaptation), and its context (the two values
// before) makes the choice a path through the level: a Viterbi search over
// the last two choices finds the best path exactly for that model.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace dbss {

struct RdoStats {
  size_t lowered = 0;     // values moved one step toward zero
  double bits_before = 0;  // the model's estimate for the rounded values
  double bits_after = 0;   // ... and for the chosen ones (the last pass's model)
};

// `scaled[i]`: odd vertex i's displacement over the level's step; `rounded`
// its plain quantized integer (quantize()); `keep[i]` non-zero: it stays as
// rounded (clamped, degenerate).  `lambda` is in squared steps per bit
// (0: nothing changes).  `passes` re-estimates the model from the previous
// pass's choice.  The result is deterministic (no threads, fixed order).
std::vector<int32_t> rdo_quantize(std::span<const double> scaled, std::span<const int32_t> rounded,
                                  std::span<const uint8_t> keep, double lambda, int passes = 2,
                                  RdoStats* stats = nullptr);

// The bits coding 2's model spends on `q`, its probabilities counted on
// `model_of` (by default q itself): the estimate rdo_quantize minimises,
// for tests and benches.
double context_model_bits(std::span<const int32_t> q, std::span<const int32_t> model_of);
inline double context_model_bits(std::span<const int32_t> q) { return context_model_bits(q, q); }

}  // namespace dbss
