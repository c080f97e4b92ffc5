// The weights of the Modified Butterfly's extraordinary rule, on their own:
// the stencil tables (butterfly.h) and the decoder's on-the-fly stencils
// both use them, and neither should need the other for it.
#pragma once

#include <cstdint>

namespace dbss {

// s_j of the extraordinary rule for valence k in 3..kMaxValence, j in 0..k-1:
// the binary64 value nearest to (1/4 + cos(2πj/k) + cos(4πj/k)/2) / k
// (k = 3: 5/12, -1/12, -1/12; k = 4: 3/8, 0, -1/8, 0).  0 outside that range.
double butterfly_weight(uint32_t k, uint32_t j) noexcept;

}  // namespace dbss
