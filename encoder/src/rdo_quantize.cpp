#include "dbss/encoder/rdo_quantize.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace dbss {

namespace {

// Coding 2's model (spec/dbss-format.md section 9b) as bit costs from
// counts: zero[c], sign[s], mag[c][j] and Exp-Golomb past 14.
constexpr int kContexts = 7, kSigns = 3, kUnary = 14;

int context_of(int32_t a, int32_t b) {
  const int64_t s = std::llabs(int64_t{a}) + std::llabs(int64_t{b});
  return static_cast<int>(std::min<int64_t>(s, kContexts - 1));
}
int sign_context(int32_t prev) { return prev == 0 ? 0 : (prev > 0 ? 1 : 2); }

// Bits of a binary decision seen n0 / n1 times, with the coder's limits on
// a probability (31..32737 of 32768) and half a count of prior each way.
double bits_of(double n_this, double n_other) {
  const double p = std::clamp((n_this + 0.5) / (n_this + n_other + 1.0), 31.0 / 32768, 32737.0 / 32768);
  return -std::log2(p);
}

class Model {
 public:
  explicit Model(std::span<const int32_t> q) {
    std::array<std::array<double, 2>, kContexts> zero{};
    std::array<std::array<double, 2>, kSigns> sign{};
    std::array<std::array<std::array<double, 2>, kUnary>, kContexts> mag{};
    int32_t q1 = 0, q2 = 0;
    for (int32_t v : q) {
      const int c = context_of(q1, q2);
      zero[c][v != 0] += 1;
      if (v != 0) {
        sign[sign_context(q1)][v < 0] += 1;
        const int64_t m = std::llabs(int64_t{v});
        for (int64_t j = 0; j < kUnary && j < m; ++j) mag[c][j][j + 1 < m] += 1;
      }
      q2 = q1;
      q1 = v;
    }
    for (int c = 0; c < kContexts; ++c) {
      zero_bits_[c][0] = bits_of(zero[c][0], zero[c][1]);
      zero_bits_[c][1] = bits_of(zero[c][1], zero[c][0]);
      // unary_[c][m]: the magnitude bits of |q| = m, m = 1..kUnary + 1 (the
      // last: all ones, Exp-Golomb after).
      double ones = 0;
      for (int j = 0; j < kUnary; ++j) {
        unary_[c][j + 1] = ones + bits_of(mag[c][j][0], mag[c][j][1]);
        ones += bits_of(mag[c][j][1], mag[c][j][0]);
      }
      unary_[c][kUnary + 1] = ones;
    }
    for (int s = 0; s < kSigns; ++s) sign_bits_[s][0] = bits_of(sign[s][0], sign[s][1]), sign_bits_[s][1] = bits_of(sign[s][1], sign[s][0]);
  }

  // Bits of `v` after q_{i-1} = q1 and q_{i-2} = q2.
  double bits(int32_t v, int32_t q1, int32_t q2) const {
    const int c = context_of(q1, q2);
    if (v == 0) return zero_bits_[c][0];
    const int64_t m = std::llabs(int64_t{v});
    double b = zero_bits_[c][1] + sign_bits_[sign_context(q1)][v < 0];
    if (m <= kUnary) return b + unary_[c][m];
    // Exp-Golomb of x = m - 14: 2e + 1 bits (their adaptive part unmodelled).
    const double e = std::floor(std::log2(double(m - kUnary)));
    return b + unary_[c][kUnary + 1] + 2 * e + 1;
  }

 private:
  std::array<std::array<double, 2>, kContexts> zero_bits_{};
  std::array<std::array<double, 2>, kSigns> sign_bits_{};
  std::array<std::array<double, kUnary + 2>, kContexts> unary_{};
};

double model_bits(const Model& model, std::span<const int32_t> q) {
  double bits = 0;
  int32_t q1 = 0, q2 = 0;
  for (int32_t v : q) {
    bits += model.bits(v, q1, q2);
    q2 = q1;
    q1 = v;
  }
  return bits;
}

}  // namespace

double context_model_bits(std::span<const int32_t> q, std::span<const int32_t> model_of) {
  return model_bits(Model(model_of), q);
}

std::vector<int32_t> rdo_quantize(std::span<const double> scaled, std::span<const int32_t> rounded,
                                  std::span<const uint8_t> keep, double lambda, int passes, RdoStats* stats) {
  const size_t n = rounded.size();
  std::vector<int32_t> q(rounded.begin(), rounded.end());
  if (stats) *stats = {};
  if (n == 0 || !(lambda > 0)) return q;
  if (stats) stats->bits_before = context_model_bits(q);
  // Candidates: [0] the rounded value, [1] one step toward zero (when it
  // differs and the vertex may move).
  const auto candidate = [&](size_t i, int k) -> int32_t {
    const int32_t r = rounded[i];
    return k == 0 ? r : r - (r > 0 ? 1 : -1);
  };
  const auto choices = [&](size_t i) { return rounded[i] != 0 && !(i < keep.size() && keep[i]) ? 2 : 1; };
  const auto distortion = [&](size_t i, int32_t v) {
    const double d = scaled[i] - v;
    return d * d;
  };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // back[i][state]: the choice of i-2 on the best path into state (choice
  // of i-1, choice of i) = 2 * k_{i-1} + k_i.
  std::vector<std::array<uint8_t, 4>> back(n);
  for (int pass = 0; pass < std::max(1, passes); ++pass) {
    const Model model(q);
    std::array<double, 4> cost;
    cost.fill(kInf);
    for (int k = 0; k < choices(0); ++k) cost[k] = distortion(0, candidate(0, k)) + lambda * model.bits(candidate(0, k), 0, 0);
    for (size_t i = 1; i < n; ++i) {
      std::array<double, 4> next;
      next.fill(kInf);
      for (int b = 0; b < choices(i - 1); ++b) {
        const int32_t q1 = candidate(i - 1, b);
        for (int x = 0; x < choices(i); ++x) {
          const int32_t v = candidate(i, x);
          const double d = distortion(i, v);
          for (int a = 0; a < 2; ++a) {
            const double from = cost[2 * a + b];
            if (from == kInf) continue;
            const int32_t q2 = i >= 2 ? candidate(i - 2, a) : 0;
            const double c = from + d + lambda * model.bits(v, q1, q2);
            if (c < next[2 * b + x]) next[2 * b + x] = c, back[i][2 * b + x] = static_cast<uint8_t>(a);
          }
        }
      }
      cost = next;
    }
    // Trace the cheapest end state back.
    int state = static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
    for (size_t i = n; i-- > 0;) {
      const int k = state & 1, b = state >> 1;
      q[i] = candidate(i, k);
      if (i == 0) break;
      state = 2 * back[i][state] + b;
    }
    if (stats) stats->bits_after = model_bits(model, q);
  }
  if (stats)
    for (size_t i = 0; i < n; ++i) stats->lowered += q[i] != rounded[i];
  return q;
}

}  // namespace dbss
