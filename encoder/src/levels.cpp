#include "dbss/encoder/levels.h"

#include <algorithm>
#include <cmath>

#include "dbss/decoder/level_refiner.h"
#include "dbss/encoder/sampling.h"
#include "dbss/format/writer.h"

namespace dbss {

Result<size_t> choose_coding(format::Level& level, int zstd_level) {
  size_t best = SIZE_MAX;
  format::DisplacementCoding best_coding = level.coding;
  for (auto coding : {format::DisplacementCoding::byte_planes, format::DisplacementCoding::varint}) {
    level.coding = coding;
    auto data = format::encode_level(level, zstd_level);
    if (!data.ok()) return data.status();
    if (data.value().size() < best) best = data.value().size(), best_coding = coding;
  }
  level.coding = best_coding;
  return best;
}

Result<EncodedLevels> encode_levels(const TriangleMesh& control, const PointIndex& points, double diagonal,
                                    const LevelEncodeOptions& o) {
  if (!(o.error > 0) || !(diagonal > 0)) return Status(ErrorCode::invalid_argument, "error and diagonal must be positive");
  auto refiner = LevelRefiner::create(control);
  if (!refiner.ok()) return refiner.status();
  LevelRefiner& r = refiner.value();
  EncodedLevels out;
  out.positions.push_back(control.positions);
  out.triangles.push_back(control.triangles);
  const float step = static_cast<float>(2 * o.error * diagonal);
  for (uint32_t l = 1; l <= o.levels; ++l) {
    if (o.on_level) o.on_level(l);
    // Per odd vertex, written by whichever thread samples it, summed after.
    const size_t odd = static_cast<size_t>(r.next_odd_count());
    std::vector<uint8_t> source(odd, 0xFF), clamped(odd, 0);
    std::vector<double> magnitude(odd, 0.0);
    // The decoder's own step: it computes each odd vertex's undisplaced
    // point and normal, this chooses q from them, and the vertex moves as a
    // decoder will move it (closed loop: later levels start from exactly
    // what a decoder computes).
    const OddChooser choose = [&](uint32_t e, const double p[3], const double n[3], const float* a, const float* b) {
      if (n[0] == 0 && n[1] == 0 && n[2] == 0) return int32_t{0};  // degenerate: the decoder will not move it
      const double len = std::sqrt(std::pow(a[0] - b[0], 2.0) + std::pow(a[1] - b[1], 2.0) + std::pow(a[2] - b[2], 2.0));
      const Sample s = sample_displacement(points, p, n, 0.5 * len, 0.5 * len);
      const double q = std::nearbyint(s.distance / step);
      const double limit = format::kMaxAbsDisplacement;
      source[e] = static_cast<uint8_t>(s.source);
      // The format's range caps q too (only with steps far below the
      // geometry's scale); counted with the sampler's clamps.
      clamped[e] = s.clamped || std::abs(q) > limit;
      magnitude[e] = std::abs(s.distance);
      return static_cast<int32_t>(std::clamp(q, -limit, limit));
    };
    format::Level level;
    level.index = static_cast<uint8_t>(l);
    level.step = step;
    r.refine(choose, step, level.q, std::max(1u, o.threads));

    LevelStats st;
    st.level = l;
    st.odd = odd;
    st.step = step;
    double sum_abs = 0;
    for (size_t e = 0; e < odd; ++e) {
      st.clamped += clamped[e];
      st.by_triangle += source[e] == static_cast<uint8_t>(SampleSource::triangle);
      st.by_plane += source[e] == static_cast<uint8_t>(SampleSource::plane);
      st.by_nearest += source[e] == static_cast<uint8_t>(SampleSource::nearest);
      sum_abs += magnitude[e];
    }
    st.mean_abs_displacement = odd ? sum_abs / odd : 0;

    auto bytes = choose_coding(level, o.zstd_level);
    if (!bytes.ok()) return bytes.status();
    st.bytes = bytes.value();
    st.coding = level.coding;

    out.positions.emplace_back(r.positions().begin(), r.positions().end());
    out.triangles.emplace_back(r.triangles().begin(), r.triangles().end());
    out.levels.push_back(std::move(level));
    out.stats.push_back(st);
  }
  return out;
}

}  // namespace dbss
