// The whole encoder: points -> control mesh stages -> Draco -> levels -> the
// bytes of a .dbss file.  `dbss encode`, `dbss compare` and the benchmarks
// all run this one pipeline.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/creases.h"
#include "dbss/encoder/control_mesh.h"
#include "dbss/encoder/control_rounding.h"
#include "dbss/encoder/levels.h"
#include "dbss/encoder/outliers.h"
#include "dbss/encoder/scan_check.h"
#include "dbss/encoder/point_index.h"
#include "dbss/encoder/point_input.h"
#include "dbss/format/container.h"
#include "dbss/format/writer.h"
#include "dbss/format/status.h"

namespace dbss {

// EncodeOptions::levels: as many levels as the points support (auto_levels).
inline constexpr uint32_t kAutoLevels = 0xFFFFFFFFu;

// Levels for `points` points over a control mesh with `control` counts: up
// to and including the first level with more vertices than there are
// points, within 1..kMaxLevelsInPractice.  Past that level the points
// cannot say more: on sampled shapes (bench/rd_bench.md) no later level
// came more than 1% closer to the true surface, while each cost 1.2-2.3x
// the bytes of the one before.
uint32_t auto_levels(const format::MeshCounts& control, size_t points);

struct EncodeOptions {
  OutlierOptions outliers;  // removed before carving unless outliers.enabled is false
  ControlMeshOptions control;
  CreaseOptions creases;  // sharp features: tags and snapping (angle <= 0: off, a 1.0 file)
  int control_bits = 0;  // Draco position bits of the control mesh, 8..30; 0: the encoder's rule (control_bits_from_level0)
  // With control.control_faces 0: also encode over a quarter of the default
  // faces and keep the better rate-distortion curve (encode.cpp,
  // choose_control; not above 2^18 points, where the second candidate
  // would cost about a whole encoding); false: the default face count, as
  // before issue 15.
  bool choose_control = true;
  // Point path: each control vertex goes to the point of Draco's grid
  // nearest its surface among those it can slide to (control_rounding.h);
  // false: Draco's own rounding to the nearest point, as before issue 15's
  // ninth session.  Off on a control mesh with crease tags (its vertices
  // are snapped onto the feature lines).
  bool round_along_surface = true;
  // Point path, control_bits 0: Draco's bits from level 0's distance to the
  // points (control_bits_for_error); false: from the step alone
  // (control_bits_for_step), as before.
  bool control_bits_from_level0 = true;
  // Point path, noisy clouds (points_are_noisy): the displacements of the
  // level that crosses the points' density averaged with their neighbours'
  // (displacement_smoothing.h), after the control choice, which compares
  // its candidates without it.  Noise 2e-3 (rd_bench): the rise past that
  // level 2.2-2.5% -> 1.6-1.8% on the eight, 17-22% fewer bytes
  // (bench/rd_bench.md, eleventh session).  Clean clouds: no change.
  bool smooth_noise = true;
  uint32_t levels = 3;    // displacement levels, 0..kMaxLevelsInFormat, or kAutoLevels
  // Quantization: `step` (model units) when > 0, else derived from `error`
  // (largest rounding error relative to the bounding-box diagonal; step = 2 *
  // error * diagonal).
  double error = 1e-4;
  double step = 0;
  int effort = 19;  // zstd level 1..22 of the displacement chunks
  unsigned threads = 2;
  std::string source_name;     // written into the `meta` chunk; may be empty
  std::string encoder_version;  // likewise
  std::function<void(const std::string&)> on_progress;  // may be empty
};

struct EncodeTimes {
  double outliers = 0, control = 0, draco = 0, levels = 0, check = 0, serialize = 0;  // seconds
  double choice = 0;  // seconds the control mesh's candidate added (the one not kept, and the comparison)
};

// Cut tubes joined (encode.cpp, join_cut_tubes): where a closed surface
// capped two rims of the points that look like a tube's cut ends, the gap
// was sampled (tube_points.h) and the surface built again from the points
// with those added: the control mesh and the levels are built on those, the
// self-check and `points` are the scan's alone.
struct TubeJoin {
  size_t tubes = 0;        // gaps joined
  size_t points = 0;       // points added in them (no scan supports them)
  double area_share = 0;   // their share of the control mesh's area, 0..1
  std::vector<float> at;   // the points added (xyz): where the encoder's own tubes run
};

struct Encoding {
  PointCloud points;              // the points the surface was built from (after outlier removal)
  TubeJoin tubes;                 // lost handles joined across gaps in the points
  OutlierStats outliers;
  CreaseStats creases;            // found on the control mesh before Draco
  ControlMeshStages stages;
  TriangleMesh control;           // the Draco-decoded control mesh the file holds
  format::FileContents contents;  // what the file holds
  std::vector<uint8_t> bytes;     // the serialized file
  std::vector<format::TocEntry> toc;  // its chunks, in file order
  ScanCheck check;                // the result against the points (warnings recorded in `meta`)
  EncodedLevels levels;           // per level: reconstruction (bit-identical to the decoder's) and stats
  double diagonal = 0;            // of the points' bounding box, model units
  float step = 0;                 // the quantization step of every level, model units (`step` or from `error`)
  int control_bits = 0;           // Draco position bits of the control mesh (given, or from the step)
  ControlRounding rounding;       // where Draco's grid put the control vertices (round_along_surface)
  uint32_t level_count = 0;       // levels in the file (given, or auto_levels)
  double error = 0;               // the error target actually used (from `step` when given)
  double noise = 0;               // the points' noise (points_noise) on a noisy cloud (points_are_noisy), else 0
  bool noisy = false;             // points_are_noisy: the levels sampled with the wide fit (encode_levels)
  bool quiet = true;              // points_are_quiet: a clean cloud's levels sampled with the tight kernel
  std::string control_choice;     // which control mesh was kept and why (EncodeOptions::choose_control; `meta` control.choice)
  EncodeTimes seconds;
};

// Runs the pipeline on `points` (already checked with check_reconstructible).
// Errors: invalid_argument for unusable points or options, internal for a
// stage that broke an invariant (a bug).
Result<Encoding> encode_points(const PointCloud& points, const EncodeOptions& options = {});
// The same with the caller's index over the points.
Result<Encoding> encode_points(const PointIndex& points, const EncodeOptions& options = {});

// Bytes of the file prefix a client needs for levels 0..level: the end of
// that level's chunk (level 0: the end of the control-mesh chunk).
uint64_t prefix_bytes(const Encoding& e, uint32_t level);

}  // namespace dbss
