// Encoder II: per level, subdivide the decoded previous level with the
// decoder's own code, sample each odd vertex's displacement along the
// decoder's normal, quantize, and continue from the dequantized result, so
// the decoder reproduces the encoder's meshes bit for bit.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/quantize.h"
#include "dbss/encoder/sampling.h"
#include "dbss/format/container.h"
#include "dbss/format/status.h"

namespace dbss {

struct LevelEncodeOptions {
  uint32_t levels = 3;
  // Quantization step of every level, model units, > 0: rounding moves a
  // vertex at most step / 2 (quantization_step() makes it from an error
  // relative to the diagonal).
  float step = 0;
  int zstd_level = 19;
  unsigned threads = 1;
  std::function<void(uint32_t level)> on_level;  // called as each level starts; may be empty
  format::Creases creases;  // the control mesh's crease tags (empty: none), as the file holds them
  bool wedge = true;        // with creases: CreaseOptions::wedge
  bool wedge_gate = true;   // ... only near a tagged edge: CreaseOptions::wedge_gate
  bool clean_away = false;  // ... one-sided only where the fit sees a feature: CreaseOptions::clean_away
  // Rate-distortion optimised quantization (rdo_quantize.h) of levels
  // rdo_first_level and finer, with this lambda in squared steps per bit;
  // 0: plain rounding.  Not with creases.
  double rdo_lambda = 0;
  // Noisy clouds: the displacements of the level that crosses the points'
  // density averaged with their neighbours' (displacement_smoothing.h);
  // false: as sampled.
  bool smooth_noise = false;
  uint32_t rdo_first_level = 1;
  // With a sampler that gives boundary values: a level writes its BDRY
  // chunk only when boundary_pays() says the error it removes is worth its
  // bytes; otherwise the level keeps the boundary rule alone (no BDRY, its
  // boundary odd vertices cast again with LevelSampler::boundary_mode
  // false).  false: BDRY wherever a value is non-zero (the 1.3 encoder's
  // rule).  Not with smoothing (its levels keep BDRY as before); RDO levels
  // take the rule too, from their planned integers.
  bool boundary_when_pays = false;
};

// Whether a level's BDRY values pay for their chunk, at the exchange rate
// of the level's own displacements.  One more bit per interior odd vertex
// halves the step, and the two-sided error it removes over the area a
// vertex covers (a_v, the level's area over its vertex count) is about
// step / 4 x ln 2 x a_v: an interior bit is worth kBoundaryBitWorth x step
// x a_v of integrated distance.  A boundary odd vertex moved across the
// boundary by d, on an edge of length h, takes away a sliver of area
// about d h whose mean distance is about d / 2: d^2 h / 2.  So the chunk
// pays when the sum of (value x step)^2 x h / 2 over its vertices (the
// `gain`) is above its bits (data, 12 frame bytes and a 16-byte table
// entry) x kBoundaryBitWorth x step x a_v (the `cost`).  A moved vertex
// is an even vertex of every finer level, and the sliver it closes stays
// closed there, so the gain counts once per prefix it improves
// (`prefixes`: this level and the finer ones the file holds).  The cost
// stays at this level's rate, where a bit buys the most error.
// Calibrated on three meshes (bench/lod_bench.md, ninth session): on
// elephant-with-holes level 1's values take 9% off every finer level's
// error for 2% of its bytes; on mech-holes-shark and armadillo with 3
// holes no level's values pay.
inline constexpr double kBoundaryBitWorth = 0.17328679513998632;  // ln 2 / 4
struct BoundaryWorth {
  double gain = 0, cost = 0;
  bool pays() const noexcept { return gain > cost; }
};
BoundaryWorth boundary_worth(std::span<const int32_t> bq, std::span<const double> edge_length, float step, size_t chunk_bytes,
                             double level_area, size_t level_vertices, uint32_t prefixes = 1);

struct LevelStats {
  uint32_t level = 0;
  size_t odd = 0;
  float step = 0;
  size_t clamped = 0, by_triangle = 0, by_plane = 0, by_nearest = 0;
  size_t fitted = 0;  // samples taken to the local surface fit (the rest: to the hit itself)
  size_t by_wedge = 0;  // of by_plane: from the two sides' planes next to a crease
  double mean_abs_displacement = 0;
  size_t rdo_lowered = 0;  // values the RDO quantizer moved one step toward zero
  size_t bytes = 0;  // LEVL chunk data
  // Format 1.3: boundary odd vertices, those with a non-zero in-surface
  // value, those whose in-surface value was clamped, and the BDRY chunk's
  // data bytes (0 when the level has none).
  size_t boundary_odd = 0, boundary_moved = 0, boundary_clamped = 0, boundary_bytes = 0;
  // With LevelEncodeOptions::boundary_when_pays: the values' worth
  // (boundary_worth) and whether they were dropped for it (then the
  // counts above are those of the level as written, without BDRY).
  BoundaryWorth boundary_worth;
  bool boundary_dropped = false;
  format::DisplacementCoding coding = format::DisplacementCoding::byte_planes;
};

struct EncodedLevels {
  std::vector<format::Level> levels;
  // chunks[i]: the LEVL chunk data of levels[i] as choose_coding compressed
  // it, for the writer to reuse (format::FileContents::level_data).
  std::vector<std::vector<uint8_t>> chunks;
  // boundary_chunks[i]: the BDRY chunk data of levels[i] (empty without
  // one), kept the same way (format::FileContents::boundary_data).
  std::vector<std::vector<uint8_t>> boundary_chunks;
  std::vector<LevelStats> stats;
  std::vector<std::vector<float>> positions;  // positions[l]: the reconstruction of level l (0 = control)
  std::vector<std::vector<uint32_t>> triangles;
  // The points' noise (points_noise, model units) when a noisy cloud's
  // levels took a step from it (kNoiseStep) instead of the options' step;
  // 0 otherwise.  For `meta` (quantization): the header's error target is
  // the one asked for, not the rounding such a file has.
  double step_noise = 0;
};

// Sets level.coding to the payload layout that makes the smallest LEVL chunk
// data and returns that data (every coding is tried; the smallest one's
// bytes are kept so nobody compresses the level again).  A level coded
// `context` needs a version 1.2 file (format::minimum_version_minor).
Result<std::vector<uint8_t>> choose_coding(format::Level& level, int zstd_level);

// Where the displacements come from: the closed loop (subdivision,
// quantization, continuing from what a decoder computes) is the same for
// every source; only the sample of each odd vertex differs.
struct LevelSampler {
  // Called before each level l >= 1 is sampled, with the level it refines
  // (l - 1, as a decoder holds it); odd vertex `odd` of level l sits on edge
  // `odd` of that mesh in the canonical edge order.  May be empty.
  std::function<void(uint32_t level, std::span<const float> positions, std::span<const uint32_t> triangles)> begin_level;
  // The signed distance along the unit normal `n` from the undisplaced odd
  // vertex `p` to the surface, clamped to half_length (half its edge's
  // length).  Called from several threads at once.
  std::function<Sample(uint32_t odd, const double p[3], const double n[3], double half_length)> sample;
  // The quantizer's dead zone in steps for a level of `odd` samples refining
  // a level of `even` vertices; empty: plain rounding (0.5).  Infinite: the
  // level stores only zeros and its vertices are not sampled.
  std::function<double(size_t odd, size_t even)> dead_zone;
  // The quantization step of level l (> 0, finite; the file stores one per
  // level) for `odd` samples refining `even` vertices; empty: the options'
  // step at every level.
  std::function<float(uint32_t level, size_t odd, size_t even)> step;
  // Format 1.3 (spec/decoding.md section 7a): the signed distance along the
  // unit in-surface direction `b` (across the boundary, outwards) from
  // boundary odd vertex `odd`, at `m` after its normal displacement, to the
  // surface's boundary, clamped to half_length.  Empty: no boundary values
  // (and no BDRY chunk).  Called from one thread, in boundary-edge order.
  // `n` is the vertex's unit normal.
  std::function<double(uint32_t odd, const double m[3], const double b[3], const double n[3], double half_length)>
      boundary;
  // With LevelEncodeOptions::boundary_when_pays: switches `sample` (for odd
  // vertices on a boundary edge) and `boundary` between aiming at BDRY
  // values (true, what begin_level leaves) and the boundary rule alone
  // (false: `boundary` returns 0, a boundary odd vertex takes its normal
  // offset as a file without BDRY would).
  std::function<void(bool values)> boundary_mode;
  // The neighbours' weight in the sampled displacements of the level that
  // crosses the points' density (`dead_zone` past 0.5 and finite:
  // smooth_displacements); 0: as sampled.
  double smoothing = 0;
};

// `control` must be the Draco-decoded control mesh.  Displacements from
// the points (sample_displacement, the dead zone past their density).
Result<EncodedLevels> encode_levels(const TriangleMesh& control, const PointIndex& points,
                                    const LevelEncodeOptions& options);
// The same with the points' noise figures measured already (point_noise(points)).
Result<EncodedLevels> encode_levels(const TriangleMesh& control, const PointIndex& points, const PointNoise& noise,
                                    const LevelEncodeOptions& options);
// The same loop with displacements from `sampler`.
Result<EncodedLevels> encode_levels(const TriangleMesh& control, const LevelSampler& sampler,
                                    const LevelEncodeOptions& options);

}  // namespace dbss
