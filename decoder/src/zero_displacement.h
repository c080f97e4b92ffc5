// Internal: when a displacement of zero can skip the normal.
//
// Section 7 places an odd vertex at round32(s + (0 * Δ) * n) when its q is
// 0.  With n finite, (0 * Δ) * n is a zero, and s + ±0 is s exactly, with
// one exception: s = -0 plus +0 is +0.  n is finite whenever every point of
// the vertex's ring is (its sums of products of binary32 differences cannot
// overflow binary64, and a zero length gives the zero normal).  So where
// the level's points are all finite, an odd vertex with q = 0 whose stencil
// point has no -0 coordinate is its stencil point, bit for bit, and its
// normal need not be computed.  Levels past the points' density are almost
// all zeros (the shipped example's levels 4 and 5 are nothing else), and
// the normal is most of their cost.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace dbss::detail {

// True when every q[0..n) is 0.
bool all_zero(const int32_t* q, size_t n) noexcept;

// True when no float of p[0..n) is infinite or NaN.
bool all_finite(const float* p, size_t n) noexcept;

// True when no float of p[0..n) is infinite, NaN or -0.
bool all_finite_no_negative_zero(const float* p, size_t n) noexcept;

// The point at `from` copied to `to` when none of its three coordinates is
// -0 (then true); else false, nothing written.
inline bool copy_unless_negative_zero(const float* from, float* to) noexcept {
  uint32_t b[3];
  std::memcpy(b, from, sizeof b);
  if ((b[0] == 0x80000000u) | (b[1] == 0x80000000u) | (b[2] == 0x80000000u)) return false;
  std::memcpy(to, b, sizeof b);
  return true;
}

}  // namespace dbss::detail
