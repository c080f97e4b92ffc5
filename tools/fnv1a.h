// FNV-1a 64 of decoded positions, as spec/decoding.md section 8 defines the
// per-level hash: the binary32 position bytes, little-endian, in vertex
// order (x, y, z), so every implementation can print the same lines.
// Standard FNV-1a 64: offset basis 0xCBF29CE484222325, prime 0x100000001B3.
#pragma once

#include <bit>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

namespace dbss::tools {

inline uint64_t fnv1a64_floats(std::span<const float> values) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (float f : values) {
    const uint32_t bits = std::bit_cast<uint32_t>(f);
    for (int k = 0; k < 4; ++k) h = (h ^ ((bits >> (8 * k)) & 0xFF)) * 0x100000001b3ull;  // little-endian bytes
  }
  return h;
}

// 16 lower-case hex digits.
inline std::string fnv1a64_hex(uint64_t h) {
  char b[20];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

}  // namespace dbss::tools
