// Little-endian loads and stores on byte buffers; internal to dbss_format.
// Byte-wise so they are independent of host endianness and alignment.
// __builtin_bit_cast, not std::bit_cast: the WebAssembly build's libc++ 13
// (emscripten 3.1.6) has no <bit> bit_cast; gcc and clang both provide it.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace dbss::format::detail {

inline uint16_t load_u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
inline uint32_t load_u32(const uint8_t* p) {
  return uint32_t{p[0]} | (uint32_t{p[1]} << 8) | (uint32_t{p[2]} << 16) | (uint32_t{p[3]} << 24);
}
inline uint64_t load_u64(const uint8_t* p) { return uint64_t{load_u32(p)} | (uint64_t{load_u32(p + 4)} << 32); }
inline float load_f32(const uint8_t* p) { return __builtin_bit_cast(float, load_u32(p)); }

inline void put_u8(std::vector<uint8_t>& out, uint8_t v) { out.push_back(v); }
inline void put_u16(std::vector<uint8_t>& out, uint16_t v) {
  out.push_back(static_cast<uint8_t>(v));
  out.push_back(static_cast<uint8_t>(v >> 8));
}
inline void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
inline void put_u64(std::vector<uint8_t>& out, uint64_t v) {
  put_u32(out, static_cast<uint32_t>(v));
  put_u32(out, static_cast<uint32_t>(v >> 32));
}
inline void put_f32(std::vector<uint8_t>& out, float v) { put_u32(out, __builtin_bit_cast(uint32_t, v)); }
inline void put_bytes(std::vector<uint8_t>& out, const void* p, size_t n) {
  // resize + memcpy rather than insert: GCC 12 warns falsely
  // (-Wstringop-overflow) on vector::insert after reserve.
  if (n == 0) return;
  const size_t at = out.size();
  out.resize(at + n);
  std::memcpy(out.data() + at, p, n);
}

}  // namespace dbss::format::detail
