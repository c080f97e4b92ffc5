#include "dbss/encoder/levels.h"

#include <algorithm>
#include <cmath>

#include "dbss/decoder/subdivision.h"
#include "dbss/encoder/sampling.h"
#include "dbss/format/writer.h"

namespace dbss {

Result<EncodedLevels> encode_levels(const TriangleMesh& control, const PointIndex& points, double diagonal,
                                    const LevelEncodeOptions& o) {
  if (!(o.error > 0) || !(diagonal > 0)) return Status(ErrorCode::invalid_argument, "error and diagonal must be positive");
  auto topo = build_topology(static_cast<uint32_t>(control.vertex_count()), control.triangles);
  if (!topo.ok()) return topo.status();
  LevelTopology t = std::move(topo).value();
  EncodedLevels out;
  out.positions.push_back(control.positions);
  out.triangles.push_back(control.triangles);
  const float step = static_cast<float>(2 * o.error * diagonal);
  for (uint32_t l = 1; l <= o.levels; ++l) {
    if (o.on_level) o.on_level(l);
    const LevelPlan plan = plan_level(t);
    const std::vector<float>& prev = out.positions.back();
    // The undisplaced level and the decoder's normals of its odd vertices.
    std::vector<float> plain;
    subdivide_geometry(plan, prev, {}, 0, plain, o.threads);
    std::vector<double> normals(3 * size_t{plan.odd_count()});
    odd_normals(plan.rings.data(), plain.data(), plan.vertex_count, 0, plan.odd_count(), normals.data());

    format::Level level;
    level.index = static_cast<uint8_t>(l);
    level.step = step;
    level.q.resize(plan.odd_count());
    LevelStats st;
    st.level = l;
    st.odd = plan.odd_count();
    st.step = step;
    double sum_abs = 0;
    for (uint32_t e = 0; e < plan.odd_count(); ++e) {
      const uint32_t h = t.edge_half[e];
      const float* a = &prev[3 * size_t{t.triangles[h]}];
      const float* b = &prev[3 * size_t{t.triangles[next_half(h)]}];
      const double len = std::sqrt(std::pow(a[0] - b[0], 2.0) + std::pow(a[1] - b[1], 2.0) + std::pow(a[2] - b[2], 2.0));
      const float* pf = &plain[3 * (size_t{plan.vertex_count} + e)];
      const double p[3] = {pf[0], pf[1], pf[2]};
      const double* n = &normals[3 * size_t{e}];
      if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;  // degenerate: the decoder will not move it
      const Sample s = sample_displacement(points, p, n, 0.5 * len, 0.5 * len);
      st.clamped += s.clamped;
      st.by_triangle += s.source == SampleSource::triangle;
      st.by_plane += s.source == SampleSource::plane;
      st.by_nearest += s.source == SampleSource::nearest;
      sum_abs += std::abs(s.distance);
      const double q = std::nearbyint(s.distance / step);
      const double limit = format::kMaxAbsDisplacement;
      // The format's range caps q too (only with steps far below the
      // geometry's scale); counted with the sampler's clamps.
      st.clamped += !s.clamped && std::abs(q) > limit;
      level.q[e] = static_cast<int32_t>(std::clamp(q, -limit, limit));
    }
    st.mean_abs_displacement = plan.odd_count() ? sum_abs / plan.odd_count() : 0;

    // Both payload layouts; keep the smaller.
    size_t best = SIZE_MAX;
    for (auto coding : {format::DisplacementCoding::byte_planes, format::DisplacementCoding::varint}) {
      level.coding = coding;
      auto data = format::encode_level(level, o.zstd_level);
      if (!data.ok()) return data.status();
      if (data.value().size() < best) best = data.value().size(), st.coding = coding;
    }
    level.coding = st.coding;
    st.bytes = best;

    // Closed loop: continue from exactly what the decoder will compute.
    std::vector<float> next;
    subdivide_geometry(plan, prev, level.q, level.step, next, o.threads);
    out.positions.push_back(std::move(next));
    t = refine_topology(t);
    out.triangles.push_back(t.triangles);
    out.levels.push_back(std::move(level));
    out.stats.push_back(st);
  }
  return out;
}

}  // namespace dbss
