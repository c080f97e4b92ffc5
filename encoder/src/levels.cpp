#include "dbss/encoder/levels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>

#include "dbss/decoder/level_refiner.h"
#include "dbss/encoder/crease_align.h"
#include "dbss/encoder/crease_lines.h"
#include "dbss/encoder/displacement_smoothing.h"
#include "dbss/encoder/quantize.h"
#include "dbss/encoder/rdo_quantize.h"
#include "dbss/encoder/sampling.h"
#include "dbss/format/writer.h"

namespace dbss {

namespace {

// The sampler's scratch space, one per thread sampling at once.  The
// refiner calls the chooser from its own threads without saying which, so
// each call borrows a free one and gives it back (a lock per sample, against
// microseconds of sampling); they live as long as the encoding.
class ScratchPool {
 public:
  SampleScratch& take() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (free_.empty()) return *all_.emplace_back(std::make_unique<SampleScratch>());
    SampleScratch& s = *free_.back();
    free_.pop_back();
    return s;
  }
  void give(SampleScratch& s) {
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(&s);
  }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<SampleScratch>> all_;
  std::vector<SampleScratch*> free_;
};

// The wedge's gate (crease_lines.h): a tagged edge reaches this many of its
// lengths, plus the radius of the wedge's own 32 points, beyond itself.
// Measured (crease_bench, creases on): at 2 the wedge samples and the bytes
// of the cube, cylinder, roof, fandisk and anchor are the same as with no
// gate; at 1 the roof and fandisk lose 0.1-0.6% of them (the wedge also
// helps beside feature lines the tags miss, between darts), at 0.5 4-5%,
// and the fandisk's level 3 rises 1.2%.
constexpr double kWedgeSlack = 2.0;
constexpr size_t kWedgeNeighbourhood = 32;

// On a noisy cloud (points_are_noisy) no level's step is finer than this
// share of the noise (points_noise): the fit's heights scatter by about a
// quarter to a half of the noise, and rounding them to a finer step codes
// that scatter as detail.  Measured (rd_bench, noise 2e-3 of the diagonal,
// knot1, seed 1; the default step is a tenth of that noise): levels 1-3 in
// 6-11% fewer bytes for 0.2-0.4% more error against the true surface, and
// the bytes at Poisson + Draco qp10's error 0.87 -> 0.82 of its.  The step
// is each LEVL's own (no format change).
constexpr double kNoiseStep = 0.25;

}  // namespace

Result<std::vector<uint8_t>> choose_coding(format::Level& level, int zstd_level) {
  std::vector<uint8_t> best;
  format::DisplacementCoding best_coding = level.coding;
  bool first = true;
  // The context coder last: on a tie the older codings keep the file
  // readable by 1.1 readers.
  for (auto coding : {format::DisplacementCoding::byte_planes, format::DisplacementCoding::varint,
                      format::DisplacementCoding::context}) {
    level.coding = coding;
    auto data = format::encode_level(level, zstd_level);
    if (!data.ok()) return data.status();
    // A tie keeps the first layout.
    if (first || data.value().size() < best.size()) best = std::move(data).value(), best_coding = coding;
    first = false;
  }
  level.coding = best_coding;
  return best;
}

namespace {

// An INDX entry (spec/dbss-format.md: INDX is 28 + 16 x N bytes).
constexpr size_t kTocEntryBytes = 16;

// The smallest BDRY chunk data for level.boundary (its coding set to it;
// the older codings on a tie, as choose_coding).
Result<std::vector<uint8_t>> smallest_boundary_chunk(format::Level& level, int zstd_level) {
  std::vector<uint8_t> best;
  format::DisplacementCoding best_coding = format::DisplacementCoding::varint;
  for (auto coding : {format::DisplacementCoding::byte_planes, format::DisplacementCoding::varint,
                      format::DisplacementCoding::context}) {
    level.boundary.coding = coding;
    auto data = format::encode_boundary(level, zstd_level);
    if (!data.ok()) return data.status();
    if (best.empty() || data.value().size() < best.size()) best = std::move(data).value(), best_coding = coding;
  }
  level.boundary.coding = best_coding;
  return best;
}

}  // namespace

BoundaryWorth boundary_worth(std::span<const int32_t> bq, std::span<const double> edge_length, float step, size_t chunk_bytes,
                             double level_area, size_t level_vertices, uint32_t prefixes) {
  BoundaryWorth w;
  for (size_t k = 0; k < bq.size() && k < edge_length.size(); ++k) {
    const double d = static_cast<double>(bq[k]) * step;
    w.gain += 0.5 * d * d * edge_length[k];
  }
  w.gain *= prefixes;
  const double bits = 8.0 * double(chunk_bytes + format::kChunkOverhead + kTocEntryBytes);
  const double per_vertex = level_vertices ? level_area / double(level_vertices) : 0.0;
  w.cost = bits * kBoundaryBitWorth * step * per_vertex;
  return w;
}

Result<EncodedLevels> encode_levels(const TriangleMesh& control, const PointIndex& points,
                                    const LevelEncodeOptions& o) {
  return encode_levels(control, points, point_noise(points), o);
}

Result<EncodedLevels> encode_levels(const TriangleMesh& control, const PointIndex& points, const PointNoise& noise,
                                    const LevelEncodeOptions& o) {
  // The scratch pool lives as long as the encoding; each sample borrows one.
  auto scratch = std::make_shared<ScratchPool>();
  // With creases, one-sided sampling: a line next to a crease sees only the
  // points of its own side (their normals agree with its own within 30
  // degrees), so the fit does not round the feature it stops at.
  auto normals = std::make_shared<std::vector<float>>();
  PointSides sides;
  auto lines = std::make_shared<CreaseLines>();
  if (!o.creases.empty()) {
    *normals = estimate_point_normals(points, std::max(1u, o.threads));
    sides = {normals.get(), std::cos(30 * 3.14159265358979323846 / 180), o.wedge};
    if (o.wedge && o.wedge_gate) {
      *lines = CreaseLines(control, o.creases, points, kWedgeSlack, kWedgeNeighbourhood);
      // (An empty set, from tags that do not fit the mesh, would gate the
      // wedge off everywhere; PointSides::lines null means no gate.)
      if (!lines->empty()) sides.lines = lines.get();
    }
    sides.clean_where_agreed = o.clean_away;
  }
  // On a noisy cloud the fit may widen (surface_fit.h); a clean one keeps
  // its narrow fits, byte for byte.
  const bool widen = noise.noisy;
  // The tight kernel where the scatter is the shape's, not mild noise's.
  const bool tight = !widen && noise.quiet;
  LevelSampler sampler;
  sampler.sample = [&points, scratch, normals, lines, sides, widen, tight](uint32_t, const double p[3], const double n[3], double half_length) {
    SampleScratch& mine = scratch->take();
    const Sample s = sample_displacement(points, p, n, half_length, half_length, mine, true, sides.normals ? &sides : nullptr, widen, tight);
    scratch->give(mine);
    return s;
  };
  if (o.smooth_noise && widen) sampler.smoothing = kNeighbourWeight;
  // On noise, every level's step is at least kNoiseStep of the noise.
  double step_noise = 0;
  if (widen) {
    step_noise = noise.noise;
    const float noisy = std::max(o.step, static_cast<float>(kNoiseStep * noise.noise));
    sampler.step = [noisy](uint32_t, size_t, size_t) { return noisy; };
    if (!(noisy > o.step)) step_noise = 0;  // the options' step after all
  }
  const size_t point_count = points.points().size();
  sampler.dead_zone = [point_count](size_t odd, size_t even) { return dead_zone_steps(odd, point_count, even); };
  auto out = encode_levels(control, sampler, o);
  if (out.ok()) out.value().step_noise = step_noise;
  return out;
}

Result<EncodedLevels> encode_levels(const TriangleMesh& control, const LevelSampler& sampler,
                                    const LevelEncodeOptions& o) {
  if (!(o.step > 0) || !std::isfinite(o.step)) return Status(ErrorCode::invalid_argument, "the step must be finite and positive");
  if (!sampler.sample) return Status(ErrorCode::invalid_argument, "no displacement sampler");
  auto refiner = LevelRefiner::create(control, o.creases);
  if (!refiner.ok()) return refiner.status();
  LevelRefiner& r = refiner.value();
  EncodedLevels out;
  out.positions.push_back(control.positions);
  out.triangles.push_back(control.triangles);
  for (uint32_t l = 1; l <= o.levels; ++l) {
    if (o.on_level) o.on_level(l);
    if (sampler.begin_level) sampler.begin_level(l, r.positions(), r.triangles());
    // Per odd vertex, written by whichever thread samples it, summed after.
    const size_t odd = static_cast<size_t>(r.next_odd_count());
    const size_t even = r.positions().size() / 3;
    const double dead_zone = sampler.dead_zone ? sampler.dead_zone(odd, even) : 0.5;
    const float step = sampler.step ? sampler.step(l, odd, even) : o.step;
    if (!(step > 0) || !std::isfinite(step)) return Status(ErrorCode::invalid_argument, "a level's step must be finite and positive");
    std::vector<uint8_t> source(odd, 0xFF), clamped(odd, 0), fitted(odd, 0), wedge(odd, 0);
    std::vector<double> magnitude(odd, 0.0);
    // With rate-distortion optimised quantization, each odd vertex's
    // displacement over the step, and which ones must keep their rounding.
    const bool rdo = o.rdo_lambda > 0 && l >= o.rdo_first_level && o.creases.empty();
    // Smoothing: on the level that crosses the points' density (its dead
    // zone past plain rounding, not yet infinite), the last that stores
    // anything, and at kBeforeCrossingWeight on the level before it when the
    // file goes on to the crossing (displacement_smoothing.h).  A first
    // pass on a copy samples every odd vertex, the averaged displacements
    // are then rounded as `choose` would have.  The next level's odd
    // vertices are this one's edges: each edge of the coarser mesh split in
    // two, and three inside each of its triangles.
    const size_t next_odd = 2 * odd + 3 * (r.triangles().size() / 3);
    const bool crossing = dead_zone > 0.5 && !std::isinf(dead_zone);
    const double next_zone = l < o.levels && dead_zone == 0.5 && sampler.dead_zone ? sampler.dead_zone(next_odd, even + odd) : 0.5;
    const bool before_crossing = next_zone > 0.5 && !std::isinf(next_zone);
    const double smooth_w = crossing ? sampler.smoothing : before_crossing && sampler.smoothing > 0 ? kBeforeCrossingWeight : 0;
    const bool smooth = smooth_w > 0 && !rdo && o.creases.empty();
    std::vector<double> sampled(smooth ? odd : 0, 0.0), zones(smooth ? odd : 0, 0.5);
    std::vector<uint8_t> sampled_ok(smooth ? odd : 0, 0);
    std::vector<double> scaled(rdo ? odd : 0, 0.0);
    std::vector<uint8_t> keep(rdo ? odd : 0, 1);
    // The decoder's own step: it computes each odd vertex's undisplaced
    // point and normal, this chooses q from them, and the vertex moves as a
    // decoder will move it (closed loop: later levels start from exactly
    // what a decoder computes).
    const OddChooser choose = [&](uint32_t e, const double p[3], const double n[3], const float* a, const float* b) {
      if (n[0] == 0 && n[1] == 0 && n[2] == 0) return int32_t{0};  // degenerate: the decoder will not move it
      if (std::isinf(dead_zone)) return int32_t{0};                 // nothing this level could store
      const double len = std::sqrt(std::pow(a[0] - b[0], 2.0) + std::pow(a[1] - b[1], 2.0) + std::pow(a[2] - b[2], 2.0));
      const Sample s = sampler.sample(e, p, n, 0.5 * len);
      // A displacement within kSpreadDeadZone standard errors of the fit is
      // not told apart from the fit's own error (noise): stored as 0.
      const double zone = std::max(dead_zone, kSpreadDeadZone * s.spread / step);
      const Quantized q = quantize(s.distance, step, zone);
      source[e] = static_cast<uint8_t>(s.source);
      fitted[e] = s.fitted;
      wedge[e] = s.wedge;
      // The format's range caps q too; counted with the sampler's clamps.
      clamped[e] = s.clamped || q.clamped;
      magnitude[e] = std::abs(s.distance);
      if (smooth) sampled[e] = s.distance, zones[e] = zone, sampled_ok[e] = !clamped[e];
      if (rdo) {
        scaled[e] = s.distance / step;
        // Only plain rounding is weighed: a dead zone's or a clamp's value stays.
        keep[e] = clamped[e] || zone != 0.5;
      }
      return q.q;
    };
    // With RDO, the level is first refined on a copy (the same points and
    // normals: they depend only on the level being refined), every vertex
    // sampled and rounded; the integers are then chosen over the whole
    // level, and the real step moves each vertex by its chosen integer.
    std::vector<int32_t> planned;
    RdoStats rdo_stats;
    if (rdo) {
      auto dry = LevelRefiner::create(TriangleMesh{std::vector<float>(r.positions().begin(), r.positions().end()),
                                                   std::vector<uint32_t>(r.triangles().begin(), r.triangles().end())});
      if (!dry.ok()) return dry.status();
      std::vector<int32_t> rounded;
      dry.value().refine(choose, step, rounded, std::max(1u, o.threads));
      planned = rdo_quantize(scaled, rounded, keep, o.rdo_lambda, 2, &rdo_stats);
    }
    if (smooth) {
      auto dry = LevelRefiner::create(TriangleMesh{std::vector<float>(r.positions().begin(), r.positions().end()),
                                                   std::vector<uint32_t>(r.triangles().begin(), r.triangles().end())});
      if (!dry.ok()) return dry.status();
      std::vector<int32_t> rounded;
      dry.value().refine(choose, step, rounded, std::max(1u, o.threads));
      const std::vector<double> averaged = smooth_displacements(dry.value().triangles(), even, sampled, sampled_ok, smooth_w);
      planned.assign(odd, 0);
      for (size_t e = 0; e < odd; ++e) planned[e] = sampled_ok[e] ? quantize(averaged[e], step, zones[e]).q : rounded[e];
    }
    const OddChooser chosen = [&](uint32_t e, const double*, const double*, const float*, const float*) { return planned[e]; };
    format::Level level;
    level.index = static_cast<uint8_t>(l);
    level.step = step;
    // Format 1.3: boundary odd vertices also move across the boundary, to
    // where the sampler's boundary curve is (rounded at the level's step).
    std::vector<int32_t> bq;
    std::vector<uint32_t> boundary_odds;  // per boundary edge, in order: its odd vertex
    std::vector<double> boundary_lengths;  // ... and its edge's length (boundary_worth)
    size_t boundary_clamped = 0;
    const BoundaryChooser bchoose = [&](uint32_t, uint32_t e, const float m[3], const double b[3], const double n[3],
                                        const float* a, const float* c) {
      const double len = std::sqrt(std::pow(a[0] - c[0], 2.0) + std::pow(a[1] - c[1], 2.0) + std::pow(a[2] - c[2], 2.0));
      boundary_odds.push_back(e);
      boundary_lengths.push_back(len);
      if (b[0] == 0 && b[1] == 0 && b[2] == 0) return int32_t{0};  // degenerate: the decoder will not move it
      const double at[3] = {m[0], m[1], m[2]};
      const Quantized q = quantize(sampler.boundary(e, at, b, n, 0.5 * len), step, 0.5);
      boundary_clamped += q.clamped;
      return q.q;
    };
    const OddChooser& odd_choice = rdo || smooth ? chosen : choose;
    const unsigned threads = std::max(1u, o.threads);
    std::vector<uint8_t> boundary_chunk;
    BoundaryWorth worth;
    bool dropped = false;
    if (!sampler.boundary) {
      r.refine(odd_choice, step, level.q, threads);
    } else if (!o.boundary_when_pays || smooth || !o.creases.empty()) {
      r.refine(odd_choice, step, level.q, bchoose, step, bq, threads);
    } else {
      // BDRY only where it pays: the level refined with its values on a
      // copy, their worth weighed, and the copy kept when they pay.
      // Otherwise only the boundary odd vertices are cast again, aiming
      // at what the boundary rule alone reaches; the others keep their
      // values (their points, normals and casts do not depend on BDRY).
      if (sampler.boundary_mode) sampler.boundary_mode(true);
      const auto P = r.positions();
      const auto T = r.triangles();
      double area = 0;
      for (size_t f = 0; f + 2 < T.size(); f += 3) {
        const float* a = &P[3 * size_t{T[f]}];
        const float* b = &P[3 * size_t{T[f + 1]}];
        const float* c = &P[3 * size_t{T[f + 2]}];
        const double u[3] = {double{b[0]} - a[0], double{b[1]} - a[1], double{b[2]} - a[2]};
        const double v[3] = {double{c[0]} - a[0], double{c[1]} - a[1], double{c[2]} - a[2]};
        area += 0.5 * std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2.0) + std::pow(u[2] * v[0] - u[0] * v[2], 2.0) +
                                std::pow(u[0] * v[1] - u[1] * v[0], 2.0));
      }
      auto trial = LevelRefiner::create(TriangleMesh{std::vector<float>(P.begin(), P.end()), std::vector<uint32_t>(T.begin(), T.end())});
      if (!trial.ok()) return trial.status();
      // With RDO the trial takes the planned integers (odd_choice), as the
      // level would without the rule.
      trial.value().refine(odd_choice, step, level.q, bchoose, step, bq, threads);
      const bool any = std::any_of(bq.begin(), bq.end(), [](int32_t v) { return v != 0; });
      if (any) {
        level.boundary.step = step;
        level.boundary.q = bq;
        auto data = smallest_boundary_chunk(level, o.zstd_level);
        if (!data.ok()) return data.status();
        boundary_chunk = std::move(data).value();
        worth = boundary_worth(bq, boundary_lengths, step, boundary_chunk.size(), area, odd + even, o.levels - l + 1);
      }
      if (!any || worth.pays()) {
        r = std::move(trial).value();
      } else {
        dropped = true;
        level.boundary = {};
        boundary_chunk.clear();
        std::vector<uint8_t> on_rim(odd, 0);
        for (uint32_t e : boundary_odds) on_rim[e] = 1;
        const std::vector<int32_t> kept = level.q;
        // The trial's finer level goes before r builds its own: both at
        // once doubled the loop's peak memory on a holed mesh.
        { const LevelRefiner dropped_trial = std::move(trial).value(); }
        if (sampler.boundary_mode) sampler.boundary_mode(false);
        const OddChooser again = [&](uint32_t e, const double p[3], const double n[3], const float* a, const float* b) {
          return on_rim[e] ? choose(e, p, n, a, b) : kept[e];
        };
        r.refine(again, step, level.q, threads);
        bq.assign(bq.size(), 0);
        boundary_clamped = 0;
      }
    }

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
      st.fitted += fitted[e];
      st.by_wedge += wedge[e];
      sum_abs += magnitude[e];
    }
    st.mean_abs_displacement = odd ? sum_abs / odd : 0;
    st.rdo_lowered = rdo_stats.lowered;

    st.boundary_odd = bq.size();
    for (int32_t v : bq) st.boundary_moved += v != 0;
    st.boundary_clamped = boundary_clamped;  // (apart: clamped counts odd vertices)
    st.boundary_worth = worth;
    st.boundary_dropped = dropped;
    if (st.boundary_moved && boundary_chunk.empty()) {
      level.boundary.step = step;
      level.boundary.q = std::move(bq);
      // Its bytes are kept for the writer (compressed once per coding).
      auto data = smallest_boundary_chunk(level, o.zstd_level);
      if (!data.ok()) return data.status();
      boundary_chunk = std::move(data).value();
    }
    st.boundary_bytes = boundary_chunk.size();

    auto chunk = choose_coding(level, o.zstd_level);
    if (!chunk.ok()) return chunk.status();
    st.bytes = chunk.value().size();
    st.coding = level.coding;
    out.chunks.push_back(std::move(chunk).value());
    out.boundary_chunks.push_back(std::move(boundary_chunk));

    out.positions.emplace_back(r.positions().begin(), r.positions().end());
    out.triangles.emplace_back(r.triangles().begin(), r.triangles().end());
    out.levels.push_back(std::move(level));
    out.stats.push_back(st);
  }
  return out;
}

}  // namespace dbss
