// Scans for zero_displacement.h: branch-free reductions, so the compiler
// vectorises them (a pass over a level's points costs a few percent of
// computing its normals).
#include "zero_displacement.h"

namespace dbss::detail {

bool all_zero(const int32_t* q, size_t n) noexcept {
  uint32_t any = 0;
  for (size_t i = 0; i < n; ++i) any |= static_cast<uint32_t>(q[i]);
  return any == 0;
}

namespace {
inline uint32_t bits(const float* p) noexcept {
  uint32_t b;
  std::memcpy(&b, p, sizeof b);
  return b;
}
}  // namespace

bool all_finite(const float* p, size_t n) noexcept {
  // Infinite or NaN: every exponent bit set.
  uint32_t bad = 0;
  for (size_t i = 0; i < n; ++i) bad |= static_cast<uint32_t>((bits(p + i) & 0x7F800000u) == 0x7F800000u);
  return bad == 0;
}

bool all_finite_no_negative_zero(const float* p, size_t n) noexcept {
  uint32_t bad = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t b = bits(p + i);
    bad |= static_cast<uint32_t>((b & 0x7F800000u) == 0x7F800000u) | static_cast<uint32_t>(b == 0x80000000u);
  }
  return bad == 0;
}

}  // namespace dbss::detail
