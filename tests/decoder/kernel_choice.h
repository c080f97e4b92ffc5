// The decoder kernels a test asks for: Kernels::baseline when the
// environment has DBSS_BASELINE_KERNELS (one CTest entry sets it to rerun
// the bit-exactness tests on the portable build), Kernels::scalar with
// DBSS_SCALAR_KERNELS and Kernels::paired with DBSS_PAIRED_KERNELS
// (WebAssembly's builds without and with SIMD), else the best the
// processor runs.  Read here, at the test level, as a tool would: the
// decoder itself only takes the option.
#pragma once

#include <cstdlib>

#include "dbss/decoder/kernels.h"

namespace dbss::test {

inline Kernels kernels_under_test() {
  static const Kernels k = std::getenv("DBSS_BASELINE_KERNELS") ? Kernels::baseline
                           : std::getenv("DBSS_SCALAR_KERNELS")  ? Kernels::scalar
                           : std::getenv("DBSS_PAIRED_KERNELS")  ? Kernels::paired
                                                                 : Kernels::best;
  return k;
}

}  // namespace dbss::test
