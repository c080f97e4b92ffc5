// dbss-format.md section 9b, written from its text: the range decoder, the
// probabilities and their update, the contexts and the binarization.
#include "levl_context.h"

namespace dbss_ref::detail {

namespace {

// "Decoder state and start" and "Decoding one bit with probability P".
struct RangeDecoder {
  std::span<const uint8_t> s;
  uint64_t p = 4;
  uint32_t range = 0xFFFFFFFFu;
  uint32_t code = 0;
  bool overrun = false;

  explicit RangeDecoder(std::span<const uint8_t> stream) : s(stream) {
    code = uint32_t{s[0]} << 24 | uint32_t{s[1]} << 16 | uint32_t{s[2]} << 8 | uint32_t{s[3]};
  }

  uint32_t decode(uint32_t probability) {
    const uint32_t bound = (range >> 15) * probability;
    uint32_t bit;
    if (code < bound) {
      bit = 0;
      range = bound;
    } else {
      bit = 1;
      code = code - bound;
      range = range - bound;
    }
    while (range < (1u << 24)) {
      range = range << 8;
      uint32_t next = 0;
      if (p == s.size()) {
        overrun = true;
      } else {
        next = s[p];
        p = p + 1;
      }
      code = (code << 8) | next;
    }
    return bit;
  }

  // "Probabilities": an adaptive one, updated after the bit.
  uint32_t adaptive(uint32_t& probability) {
    const uint32_t bit = decode(probability);
    if (bit == 0) probability = probability + ((32768 - probability) >> 5);
    else probability = probability - (probability >> 5);
    return bit;
  }
  uint32_t fixed() { return decode(16384); }
};

int64_t magnitude(int64_t q) { return q < 0 ? -q : q; }

}  // namespace

const char* decode_context_stream(std::span<const uint8_t> stream, uint64_t n, std::vector<int32_t>& q) {
  // "The model": every probability starts at 16384 in each chunk.
  uint32_t zero[7], sign[3], mag[7][14], exp[25];
  for (auto& v : zero) v = 16384;
  for (auto& v : sign) v = 16384;
  for (auto& row : mag)
    for (auto& v : row) v = 16384;
  for (auto& v : exp) v = 16384;

  RangeDecoder rc(stream);
  q.assign(n, 0);
  for (uint64_t i = 0; i < n; ++i) {
    const int64_t before1 = i >= 1 ? q[i - 1] : 0;
    const int64_t before2 = i >= 2 ? q[i - 2] : 0;
    const int64_t sum = magnitude(before1) + magnitude(before2);
    const uint32_t c = sum < 6 ? uint32_t(sum) : 6u;
    const uint32_t s = before1 == 0 ? 0 : before1 > 0 ? 1 : 2;
    // Step 1.
    if (rc.adaptive(zero[c]) == 0) {
      if (rc.overrun) return "compression";
      q[i] = 0;
      continue;
    }
    // Step 2.
    const uint32_t negative = rc.adaptive(sign[s]);
    // Step 3.
    int64_t m = 1;
    while (m <= 14) {
      if (rc.adaptive(mag[c][m - 1]) == 0) break;
      m = m + 1;
    }
    // Step 4.
    if (m == 15) {
      uint32_t e = 0;
      while (e <= 24) {
        if (rc.adaptive(exp[e]) == 0) break;
        e = e + 1;
      }
      if (rc.overrun) return "compression";
      if (e == 25) return "bad_field";
      int64_t x = 1;
      for (uint32_t k = 0; k < e; ++k) x = 2 * x + rc.fixed();
      m = 14 + x;
    }
    if (rc.overrun) return "compression";
    if (m > (int64_t{1} << 24)) return "bad_field";
    // Step 5.
    q[i] = int32_t(negative ? -m : m);
  }
  // "Termination": every byte used.
  if (rc.p != stream.size()) return "compression";
  return "";
}

}  // namespace dbss_ref::detail
