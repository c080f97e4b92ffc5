// Butterfly weights: the table scripts/gen_butterfly_weights.py generated, looked up.
#include "butterfly_weight.h"

#include "dbss/decoder/topology.h"  // kMaxValence

namespace dbss {

namespace {
#include "butterfly_weights.inc"
}  // namespace

double butterfly_weight(uint32_t k, uint32_t j) noexcept {
  if (k < 3 || k > kMaxValence || j >= k) return 0.0;
  return kButterflyWeights[kButterflyWeightOffset[k] + j];
}

}  // namespace dbss
