#include "odd_vertices.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif
#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#endif

#include "butterfly_terms.h"
#include "zero_displacement.h"

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

// A point as three binary64 values, for the scalar kernels: the same lane
// operations as D4's, without the ignored fourth lane.  (Outside the
// anonymous namespace: the kernels' structs hold it.)
struct P3 {
  double v[3];
  double operator[](int i) const { return v[i]; }
};
inline P3 operator+(P3 a, P3 b) { return P3{{a.v[0] + b.v[0], a.v[1] + b.v[1], a.v[2] + b.v[2]}}; }
inline P3 operator-(P3 a, P3 b) { return P3{{a.v[0] - b.v[0], a.v[1] - b.v[1], a.v[2] - b.v[2]}}; }
inline P3 operator*(P3 a, P3 b) { return P3{{a.v[0] * b.v[0], a.v[1] * b.v[1], a.v[2] * b.v[2]}}; }
inline P3 operator*(double w, P3 a) { return P3{{w * a.v[0], w * a.v[1], w * a.v[2]}}; }
inline P3 operator*(P3 a, double w) { return P3{{a.v[0] * w, a.v[1] * w, a.v[2] * w}}; }

// WebAssembly runs the scalar or the paired kernels whatever the choice
// (four-lane vectors there were measured no faster), so it does not ship
// this copy.
#if !defined(__wasm__)
#define DBSS_HAVE_VECTOR_KERNELS 1
#define DBSS_KERNEL_SCALAR 0
namespace kernels_generic {
#define DBSS_KERNEL_AVX2 0
#include "odd_vertex_kernels.inc"
#undef DBSS_KERNEL_AVX2
}  // namespace kernels_generic
#undef DBSS_KERNEL_SCALAR
#endif

// Three scalar lanes: Kernels::scalar (the tests check its bits against
// the same goldens); and two edges per two-lane vector, Kernels::paired,
// WebAssembly's kernels where it has SIMD.
#define DBSS_KERNEL_SCALAR 1
#define DBSS_KERNEL_AVX2 0
namespace kernels_scalar {
#include "odd_vertex_kernels.inc"
#include "odd_vertex_pairs.inc"
}  // namespace kernels_scalar
#undef DBSS_KERNEL_AVX2
#undef DBSS_KERNEL_SCALAR
#define DBSS_KERNEL_SCALAR 0

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
#undef DBSS_KERNEL_SCALAR

OddVertexKernels select_kernels(Kernels choice) {
  const OddVertexKernels scalar{kernels_scalar::stencil_points, kernels_scalar::displaced_points,
                                kernels_scalar::displaced_points_chosen};
  const OddVertexKernels paired{kernels_scalar::stencil_points_paired, kernels_scalar::displaced_points_paired,
                                kernels_scalar::displaced_points_chosen_paired};
  if (choice == Kernels::paired) return paired;
#ifndef DBSS_HAVE_VECTOR_KERNELS
#if defined(__wasm_simd128__)
  return choice == Kernels::scalar ? scalar : paired;
#else
  (void)choice;
  return scalar;
#endif
#else
  if (choice == Kernels::scalar) return scalar;
#ifdef DBSS_HAVE_AVX2_KERNELS
  static const bool cpu = __builtin_cpu_supports("avx2");
  if (choice == Kernels::best && cpu)
    return {kernels_avx2::stencil_points, kernels_avx2::displaced_points, kernels_avx2::displaced_points_chosen};
#endif
  return {kernels_generic::stencil_points, kernels_generic::displaced_points, kernels_generic::displaced_points_chosen};
#endif
}

}  // namespace dbss::detail
