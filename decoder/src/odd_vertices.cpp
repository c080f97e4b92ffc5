#include "odd_vertices.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "butterfly_terms.h"

// AVX-sized vectors are passed by value only between functions of one
// instruction set (see odd_vertex_kernels.inc), so the warning that their
// calling convention depends on it does not apply.
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wpsabi"
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace dbss::detail {

namespace {
// Points are processed as four binary64 lanes (x, y, z and one lane that
// is ignored) with GCC/Clang vector extensions: each lane performs exactly
// the spec's scalar operation for its coordinate, so the result is the same
// bits as scalar code, and the same source compiles for every instruction
// set (the baseline splits each operation in two SSE2 instructions, AVX2
// does it in one).  No FMA: the build has -ffp-contract=off, and AVX2 alone
// does not enable FMA instructions.
typedef double D4 __attribute__((vector_size(32)));
typedef float F4 __attribute__((vector_size(16)));
}  // namespace

namespace kernels_generic {
#define DBSS_KERNEL_AVX2 0
#include "odd_vertex_kernels.inc"
#undef DBSS_KERNEL_AVX2
}  // namespace kernels_generic

// The same kernels for AVX2, chosen at run time; tests run both
// (Kernels::baseline forces the baseline) against the same golden bits.
#if defined(__x86_64__) && defined(__GNUC__)
#define DBSS_HAVE_AVX2_KERNELS 1
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
namespace kernels_avx2 {
#define DBSS_KERNEL_AVX2 1
#include "odd_vertex_kernels.inc"
#undef DBSS_KERNEL_AVX2
}  // namespace kernels_avx2
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#endif

OddVertexKernels select_kernels(Kernels choice) {
#ifdef DBSS_HAVE_AVX2_KERNELS
  static const bool cpu = __builtin_cpu_supports("avx2");
  if (choice == Kernels::best && cpu)
    return {kernels_avx2::stencil_points, kernels_avx2::displaced_points, kernels_avx2::displaced_points_chosen};
#else
  (void)choice;
#endif
  return {kernels_generic::stencil_points, kernels_generic::displaced_points, kernels_generic::displaced_points_chosen};
}

}  // namespace dbss::detail
