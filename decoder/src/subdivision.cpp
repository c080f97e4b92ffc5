#include "dbss/decoder/subdivision.h"

#include <cstring>

#include "parallel.h"

namespace dbss {

LevelPlan plan_level(const LevelTopology& t) {
  LevelPlan plan;
  plan.vertex_count = t.vertex_count;
  plan.stencils = build_stencils(t);
  plan.rings = build_odd_rings(t);
  return plan;
}

using detail::parallel_ranges;

void subdivide_geometry(const LevelPlan& plan, std::span<const float> positions, std::span<const int32_t> q,
                        float step, std::vector<float>& out, unsigned threads) {
  const uint32_t evens = plan.vertex_count, odds = plan.odd_count();
  out.resize(3 * (size_t{evens} + odds));
  std::memcpy(out.data(), positions.data(), sizeof(float) * 3 * size_t{evens});
  float* p = out.data();
  float* odd = p + 3 * size_t{evens};
  // Pass 1: every odd vertex at its stencil point (normals need all of them).
  const Stencils& st = plan.stencils;
  const uint32_t regular = static_cast<uint32_t>(st.regular_odd.size());
  const uint32_t other = static_cast<uint32_t>(st.other_odd.size());
  parallel_ranges(regular, threads, [&](uint32_t b, uint32_t e) { apply_stencils(st, p, b, e, 0, 0, odd); });
  apply_stencils(st, p, 0, 0, 0, other, odd);
  if (q.empty()) return;
  // Pass 2: normals from the undisplaced level, then the displacements.  The
  // normals of a range are kept aside so no vertex moves before every normal
  // that reads it is computed.
  std::vector<double> normals(3 * size_t{odds});
  parallel_ranges(odds, threads, [&](uint32_t b, uint32_t e) {
    odd_normals(plan.rings.data(), p, evens, b, e, normals.data() + 3 * size_t{b});
  });
  const double delta = step;
  parallel_ranges(odds, threads, [&](uint32_t b, uint32_t e) {
    for (uint32_t i = b; i < e; ++i) {
      const double d = static_cast<double>(q[i]) * delta;
      float* v = odd + 3 * size_t{i};
      const double* n = normals.data() + 3 * size_t{i};
      v[0] = static_cast<float>(v[0] + d * n[0]);
      v[1] = static_cast<float>(v[1] + d * n[1]);
      v[2] = static_cast<float>(v[2] + d * n[2]);
    }
  });
}

}  // namespace dbss
