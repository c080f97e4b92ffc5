#include "dbss/encoder/displacement_smoothing.h"

namespace dbss {

std::vector<double> smooth_displacements(std::span<const uint32_t> refined, size_t even, std::span<const double> d,
                                         std::span<const uint8_t> ok, double w) {
  const size_t odd = d.size();
  std::vector<double> sum(odd, 0.0);
  std::vector<uint32_t> count(odd, 0);
  // Each interior odd-odd edge is seen from its two triangles: both ends
  // count each other twice, which leaves the mean as it is.
  for (size_t f = 0; f + 2 < refined.size(); f += 3)
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = refined[f + c], b = refined[f + (c + 1) % 3];
      if (a < even || b < even) continue;
      const size_t ea = a - even, eb = b - even;
      if (ea >= odd || eb >= odd || !ok[ea] || !ok[eb]) continue;
      sum[ea] += d[eb], ++count[ea];
      sum[eb] += d[ea], ++count[eb];
    }
  std::vector<double> out(d.begin(), d.end());
  for (size_t e = 0; e < odd; ++e)
    if (ok[e] && count[e] > 0) out[e] = (1 - w) * d[e] + w * sum[e] / count[e];
  return out;
}

}  // namespace dbss
