#include "context_coding.h"

#include <algorithm>
#include <array>
#include <string>

#include "dbss/format/container.h"

namespace dbss::format::detail {

namespace {

// The model of spec section 9b.  Probabilities are of a 0 bit in units of
// 2^-15; an adaptive one moves 1/32 of the way towards each bit it codes,
// so it never reaches 0 or 2^15 and every bit stays codable.  15 bits, not
// LZMA's 11: a level past the points' density is 99% zeros, and 11 bits
// cannot code a zero in under 0.022 bits (15 bits: 0.0014).
constexpr uint32_t kProbBits = 15;
constexpr uint16_t kHalf = 1u << (kProbBits - 1);
constexpr uint32_t kAdaptShift = 5;
constexpr uint32_t kTop = 1u << 24;  // the range is renormalised below this
constexpr int kUnary = 14;           // magnitudes 1..14 in unary; 14 ones: 15 or more, Exp-Golomb follows
constexpr int kMaxExponent = 24;     // |q| <= 2^24 needs at most 24 suffix bits
constexpr uint32_t kClasses = 7;

// Context: the sum of the previous two magnitudes, 0..6 (6: 6 or more).
// Neighbours in odd-vertex order lie on edges of the same or an adjacent
// parent triangle (decoding.md section 4), so their sizes predict this one.
// (Measured against the previous value alone, the two as a 3x3 pair, three
// values, and the magnitudes at the edge's end vertices: bench/entropy.md.)
inline uint32_t context_of(uint32_t m1, uint32_t m2) {
  const uint64_t sum = uint64_t{m1} + m2;
  return sum < kClasses - 1 ? static_cast<uint32_t>(sum) : kClasses - 1;
}
struct Model {
  std::array<uint16_t, kClasses> zero;
  std::array<uint16_t, 3> sign;  // by the sign of the previous value: 0, +, -
  std::array<std::array<uint16_t, kUnary>, kClasses> magnitude;
  std::array<uint16_t, kMaxExponent + 1> exponent;
  Model() {
    zero.fill(kHalf);
    sign.fill(kHalf);
    for (auto& m : magnitude) m.fill(kHalf);
    exponent.fill(kHalf);
  }
};

inline uint32_t magnitude_of(int32_t v) { return v < 0 ? 0u - static_cast<uint32_t>(v) : static_cast<uint32_t>(v); }
inline uint32_t sign_class(int32_t v) { return v == 0 ? 0 : v > 0 ? 1 : 2; }

inline void adapt(uint16_t& p, uint32_t bit) {
  if (bit) p = static_cast<uint16_t>(p - (p >> kAdaptShift));
  else p = static_cast<uint16_t>(p + (((1u << kProbBits) - p) >> kAdaptShift));
}

class Encoder {
 public:
  void bit(uint16_t& p, uint32_t b) {
    put(p, b);
    adapt(p, b);
  }
  // A bit of probability 1/2, not adapted.
  void even(uint32_t b) { put(kHalf, b); }
  std::vector<uint8_t> finish() {
    for (int i = 0; i < 5; ++i) shift_low();
    return std::move(out_);
  }

 private:
  void put(uint32_t p, uint32_t b) {
    const uint32_t bound = (range_ >> kProbBits) * p;
    if (b) low_ += bound, range_ -= bound;
    else range_ = bound;
    while (range_ < kTop) range_ <<= 8, shift_low();
  }
  // Emits the top byte of `low_`, holding back a run of 0xFF bytes until it
  // is known whether a carry will reach them.
  void shift_low() {
    if (static_cast<uint32_t>(low_) < 0xFF000000u || (low_ >> 32) != 0) {
      const auto carry = static_cast<uint8_t>(low_ >> 32);
      uint8_t byte = cache_;
      do {
        emit(static_cast<uint8_t>(byte + carry));
        byte = 0xFF;
      } while (--pending_ != 0);
      cache_ = static_cast<uint8_t>(low_ >> 24);
    }
    ++pending_;
    low_ = (low_ & 0x00FFFFFFu) << 8;
  }
  // The first byte is the cache's initial zero, which no carry can reach
  // (the coded number is below 1): the spec leaves it out.
  void emit(uint8_t b) {
    if (first_) first_ = false;
    else out_.push_back(b);
  }
  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;
  uint64_t pending_ = 1;
  bool first_ = true;
  std::vector<uint8_t> out_;
};

class Decoder {
 public:
  explicit Decoder(std::span<const uint8_t> s) : s_(s) {
    code_ = (uint32_t{s[0]} << 24) | (uint32_t{s[1]} << 16) | (uint32_t{s[2]} << 8) | s[3];
    at_ = 4;
  }
  uint32_t bit(uint16_t& p) {
    const uint32_t b = get(p);
    adapt(p, b);
    return b;
  }
  uint32_t even() { return get(kHalf); }
  // Decodes 0 bits of the adaptive probability p while they come, up to n
  // of them: exactly bit(p) repeated until it would give a 1 (that bit is
  // left for bit() to decode) or n are done, or a byte past the end was
  // needed (overrun(), the last 0 counted).  Returns how many.  Why: a
  // level past the points' density is mostly zeros in context 0, and this
  // loop keeps the state in registers instead of going through the model
  // and the general path for each (the same arithmetic, the same bits).
  size_t zeros(uint16_t& p, size_t n) {
    uint32_t range = range_, code = code_, prob = p;
    size_t k = 0;
    while (k < n) {
      const uint32_t bound = (range >> kProbBits) * prob;
      if (code >= bound) break;
      range = bound;
      prob += ((1u << kProbBits) - prob) >> kAdaptShift;  // adapt(p, 0)
      ++k;
      while (range < kTop) {
        uint32_t next = 0;
        if (at_ < s_.size()) next = s_[at_++];
        else overrun_ = true;
        range <<= 8;
        code = (code << 8) | next;
      }
      if (overrun_) break;
    }
    range_ = range, code_ = code, p = static_cast<uint16_t>(prob);
    return k;
  }
  bool overrun() const { return overrun_; }
  size_t at() const { return at_; }

 private:
  uint32_t get(uint32_t p) {
    const uint32_t bound = (range_ >> kProbBits) * p;
    uint32_t b;
    if (code_ < bound) range_ = bound, b = 0;
    else code_ -= bound, range_ -= bound, b = 1;
    while (range_ < kTop) {
      // Past the end: the caller reports it; zeros keep the state defined.
      uint32_t next = 0;
      if (at_ < s_.size()) next = s_[at_++];
      else overrun_ = true;
      range_ <<= 8;
      code_ = (code_ << 8) | next;
    }
    return b;
  }
  std::span<const uint8_t> s_;
  size_t at_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint32_t code_ = 0;
  bool overrun_ = false;
};

}  // namespace

std::vector<uint8_t> context_encode(std::span<const int32_t> q) {
  Model m;
  Encoder e;
  int32_t prev1 = 0, prev2 = 0;
  for (int32_t v : q) {
    const uint32_t c = context_of(magnitude_of(prev1), magnitude_of(prev2));
    const uint32_t mag = magnitude_of(v);
    e.bit(m.zero[c], mag != 0);
    if (mag != 0) {
      e.bit(m.sign[sign_class(prev1)], v < 0);
      int j = 1;
      for (; j <= kUnary; ++j) {
        e.bit(m.magnitude[c][j - 1], mag > static_cast<uint32_t>(j));
        if (mag == static_cast<uint32_t>(j)) break;
      }
      if (j > kUnary) {
        // Exp-Golomb of order 0: x + 1 has e + 1 binary digits.
        const uint32_t x1 = mag - (kUnary + 1) + 1;
        int exp = 0;
        while ((x1 >> (exp + 1)) != 0) ++exp;
        for (int k = 0; k < exp; ++k) e.bit(m.exponent[k], 1);
        e.bit(m.exponent[exp], 0);
        for (int k = exp - 1; k >= 0; --k) e.even((x1 >> k) & 1);
      }
    }
    prev2 = prev1, prev1 = v;
  }
  return e.finish();
}

Status context_decode(std::span<const uint8_t> stream, size_t count, uint64_t at, std::vector<int32_t>& q) {
  if (stream.size() < 4)
    return Status(ErrorCode::compression, "LEVL: coded stream of " + std::to_string(stream.size()) +
                                              " bytes, shorter than the coder's 4 starting bytes",
                  at + stream.size());
  auto overrun = [&](size_t i) {
    return Status(ErrorCode::compression, "LEVL: coded stream ends inside displacement #" + std::to_string(i),
                  at + stream.size());
  };
  Model m;
  Decoder d(stream);
  q.assign(count, 0);  // zeros: the runs below skip their entries
  uint32_t prev1 = 0, prev2 = 0, prev_sign = 0;
  for (size_t i = 0; i < count; ++i) {
    if (prev1 == 0 && prev2 == 0) {
      // A run of zeros in context 0 (prev_sign is 0 here already).
      i += d.zeros(m.zero[0], count - i);
      if (d.overrun()) return overrun(i - 1);
      if (i == count) break;
    }
    const uint32_t c = context_of(prev1, prev2);
    int32_t v = 0;
    uint32_t mag = 0;
    if (d.bit(m.zero[c])) {
      const uint32_t negative = d.bit(m.sign[prev_sign]);
      mag = 1;
      while (mag <= static_cast<uint32_t>(kUnary) && d.bit(m.magnitude[c][mag - 1])) ++mag;
      if (mag > static_cast<uint32_t>(kUnary)) {
        int exp = 0;
        while (exp <= kMaxExponent && d.bit(m.exponent[exp])) ++exp;
        // A byte needed past the end is reported before a bad value, since
        // the value was decoded from bytes that are not there.
        if (d.overrun()) return overrun(i);
        if (exp > kMaxExponent)
          return Status(ErrorCode::bad_field,
                        "LEVL: displacement #" + std::to_string(i) + " has an Exp-Golomb prefix over 24",
                        at + d.at());
        uint32_t x1 = 1;
        for (int k = 0; k < exp; ++k) x1 = (x1 << 1) | d.even();
        mag = (kUnary + 1) + (x1 - 1);
        if (d.overrun()) return overrun(i);
        if (mag > static_cast<uint32_t>(kMaxAbsDisplacement))
          return Status(ErrorCode::bad_field,
                        "LEVL: displacement #" + std::to_string(i) + " is outside -2^24..2^24", at + d.at());
      }
      v = negative ? -static_cast<int32_t>(mag) : static_cast<int32_t>(mag);
      prev_sign = negative ? 2 : 1;
    } else {
      prev_sign = 0;
    }
    if (d.overrun()) return overrun(i);
    q[i] = v;
    prev2 = prev1, prev1 = mag;
  }
  if (d.at() != stream.size())
    return Status(ErrorCode::compression,
                  "LEVL: " + std::to_string(stream.size() - d.at()) + " bytes after the last coded displacement",
                  at + d.at());
  return {};
}

}  // namespace dbss::format::detail
