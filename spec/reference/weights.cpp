// decoding.md section 5.3: the extraordinary-vertex weights s_j(k).
//
// The spec asks for the binary64 value nearest to the exact real number and
// forbids libm's cos. The project tabulates them with a script; to stay
// independent of that table this file computes them itself, once, in
// binary128 (GCC/Clang's __float128, done in software by libgcc): a Taylor
// series for cos on [0, pi/2] carries about 110 good bits, so rounding the
// result to binary64 gives the nearest value unless the exact value lies
// within ~2^-100 (relative) of a midpoint between two doubles. That is
// checked for every weight and would abort, never silently round wrongly.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "topology.h"

namespace dbss_ref::detail {

namespace {

__extension__ typedef __float128 quad;

// pi to ~107 bits as the exact sum of two doubles.
quad pi_quad() { return quad(3.141592653589793116) + quad(1.2246467991473532e-16); }

quad abs_q(quad x) { return x < 0 ? -x : x; }

// cos(x) for 0 <= x <= pi/2, by its Taylor series.
quad cos_small(quad x) {
  quad term = 1, sum = 1;
  const quad x2 = x * x;
  for (int n = 1; n < 40; ++n) {
    term = -term * x2 / quad((2 * n - 1) * (2 * n));
    sum += term;
  }
  return sum;
}

// cos(2*pi*m/k) for integers m, k > 0, using cos's symmetries so that the
// series only sees angles in [0, pi/2].
quad cos_turn(uint32_t m, uint32_t k) {
  m %= k;
  if (2 * m > k) m = k - m;  // cos(2pi - x) = cos x: now 2pi*m/k in [0, pi]
  // Angle pi * (2m/k). If 2m/k > 1/2, use cos(pi - x) = -cos x.
  if (4 * m > k) return -cos_small(pi_quad() * quad(k - 2 * m) / quad(k));
  return cos_small(pi_quad() * quad(2 * m) / quad(k));
}

double nearest_double(quad x, uint32_t k, uint32_t j) {
  const double d = static_cast<double>(x);  // binary128 -> binary64, to nearest
  // Guard against double rounding: the exact value must not be so close to
  // a midpoint that the ~2^-105 error of x could move it across.
  const double toward = std::nextafter(d, x > quad(d) ? INFINITY : -INFINITY);
  const quad half = abs_q(quad(toward) - quad(d)) / 2;
  const quad margin = abs_q(abs_q(x - quad(d)) - half);
  if (margin < half * quad(1.0 / (1ull << 40)) || d == 0.0) {
    std::fprintf(stderr, "dbss_ref: butterfly weight k=%u j=%u cannot be rounded safely\n", k, j);
    std::abort();
  }
  return d;
}

struct Table {
  std::vector<std::vector<double>> s;  // s[k][j]
  Table() : s(65) {
    s[3] = {5.0 / 12, -1.0 / 12, -1.0 / 12};  // exact fractions, correctly rounded
    s[4] = {3.0 / 8, 0.0, -1.0 / 8, 0.0};
    for (uint32_t k = 5; k <= 64; ++k) {
      for (uint32_t j = 0; j < k; ++j) {
        const quad v = (quad(1) / 4 + cos_turn(j, k) + cos_turn(2 * j, k) / 2) / quad(k);
        s[k].push_back(nearest_double(v, k, j));
      }
    }
  }
};

}  // namespace

double butterfly_weight(uint32_t k, uint32_t j) {
  static const Table table;
  return table.s.at(k).at(j);
}

}  // namespace dbss_ref::detail
