#include "dbss/measure/compare.h"

#include <memory>

#include "dbss/decoder/control_mesh.h"
#include "dbss/encoder/control_mesh_codec.h"
#include "dbss/measure/dss_baseline.h"
#include "dbss/encoder/point_index.h"

namespace dbss {

namespace {
RelativeError relative(const PointIndex& index, const TriangleMesh& mesh, double diagonal) {
  const TwoSidedDistance d = two_sided_distance(index, mesh);
  return {d.points_to_mesh_mean / diagonal, d.mean() / diagonal, d.hausdorff() / diagonal};
}
}  // namespace

Result<Comparison> compare_representations(const PointCloud& points, const EncodeOptions& eo, const CompareOptions& o) {
  if (points.size() == 0) return Status(ErrorCode::invalid_argument, "no points");
  const PointIndex input_index(points);
  auto encoded = encode_points(input_index, eo);
  if (!encoded.ok()) return encoded.status();
  Comparison c;
  c.encoding = std::move(encoded).value();
  const Encoding& e = c.encoding;
  // Every representation is sampled and measured on the points dbss was
  // built from: stray points the encoder dropped would otherwise pull the
  // baseline's samples and everyone's errors.
  std::unique_ptr<PointIndex> cleaned;
  if (e.points.size() != points.size()) cleaned = std::make_unique<PointIndex>(e.points);
  const PointIndex& index = cleaned ? *cleaned : input_index;
  const uint32_t levels = static_cast<uint32_t>(e.levels.levels.size());
  // The step dbss's levels used: a noisy cloud's levels round at a step
  // from the points' noise, coarser than e.step (levels.cpp).
  const float step = levels ? e.levels.levels[0].step : e.step;
  std::vector<DssLevel> dss;
  if (levels) {
    if (o.on_progress) o.on_progress("full-vertex DSS baseline");
    // Sampled as dbss's levels were (encode_levels): the wide fit on a
    // noisy cloud, the tight kernel and the facet hit on a quiet clean one.
    // With the clean defaults on noise, the baseline's samples followed the
    // noise (issue 15 review).  A file with crease tags sampled one-sided
    // with the narrow kernel (sampling.cpp); the baseline has no sides, so it
    // keeps at least the narrow kernel there rather than the tight one.
    DssOptions dso{levels, step, eo.effort};
    dso.widen = e.noisy;
    dso.tight = !e.noisy && e.quiet && e.contents.creases.empty();
    auto d = encode_dss_baseline(e.control, index, dso);
    if (!d.ok()) return d.status();
    dss = std::move(d).value();
  }
  const uint64_t base = prefix_bytes(e, 0);
  uint64_t dss_all = base;
  for (uint32_t l = 0; l <= levels; ++l) {
    if (o.on_progress) o.on_progress("measuring level " + std::to_string(l) + " of " + std::to_string(levels));
    CompareRow r;
    r.level = l;
    const TriangleMesh mesh{e.levels.positions[l], e.levels.triangles[l]};
    r.vertices = mesh.vertex_count();
    r.triangles = mesh.triangle_count();
    r.dbss_bytes = prefix_bytes(e, l);
    if (l == 0) {
      r.dss_level_bytes = r.dss_all_bytes = base;
    } else {
      const DssLevel& d = dss[l - 1];
      r.dbss_samples = e.levels.stats[l - 1].odd;
      r.dbss_clamped = e.levels.stats[l - 1].clamped;
      r.dss_samples = d.samples;
      r.dss_clamped = d.clamped;
      r.dss_level_bytes = base + d.bytes;
      dss_all += d.bytes;
      r.dss_all_bytes = dss_all;
    }
    if (o.errors) {
      r.dbss_error = relative(index, mesh, e.diagonal);
      r.dss_error = l == 0 ? r.dbss_error : relative(index, dss[l - 1].mesh, e.diagonal);
    }
    for (int bits : o.draco_bits) {
      auto bytes = encode_control_mesh(mesh, {bits, 0});
      if (!bytes.ok()) return bytes.status();
      r.draco_bytes.push_back(bytes.value().size());
      if (o.errors) {
        auto back = decode_control_mesh(bytes.value(), uint64_t{1} << 32, uint64_t{1} << 32);
        if (!back.ok()) return Status(ErrorCode::internal, "Draco round trip of level " + std::to_string(l) + ": " + back.status().to_string());
        r.draco_error.push_back(relative(index, back.value(), e.diagonal));
      }
    }
    c.rows.push_back(std::move(r));
  }
  return c;
}

}  // namespace dbss
