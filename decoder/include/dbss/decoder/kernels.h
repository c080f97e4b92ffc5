// Which compiled version of the decoder's inner loops runs.  Every choice
// computes the same IEEE operations in the same order, so the output bits
// are the same; the choice is for speed, and for tests that check that claim.
#pragma once

#include <cstdint>

namespace dbss {

enum class Kernels : uint8_t {
  best,      // the fastest the processor runs: AVX2 on x86-64 where it has it, else baseline
  baseline,  // the portable build (SSE2 on x86-64), on any processor
  scalar,    // three scalar lanes per point, no vectors: WebAssembly without SIMD
  paired,    // two edges per two-lane vector: WebAssembly with SIMD (any choice but scalar)
};

}  // namespace dbss
