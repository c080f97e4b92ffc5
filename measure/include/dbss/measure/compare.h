// dbss against the alternatives, level by level, from one encoding: the
// full-vertex DSS baseline (same control mesh, sampler, quantizer and entropy
// coder) and Draco on the identical dbss level mesh.  Backs `dbss compare`
// and the benchmark table.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dbss/encoder/encode.h"
#include "dbss/measure/surface_distance.h"

namespace dbss {

struct CompareOptions {
  std::vector<int> draco_bits = {11, 14};  // Draco position quantization of the level meshes
  bool errors = true;                      // compute the distance figures (the slow part)
  std::function<void(const std::string&)> on_progress;  // called as each level is measured; may be empty
};

// Errors relative to the bounding-box diagonal.
struct RelativeError {
  double to_surface = 0;  // mean distance from the points to the surface (the informative direction)
  double mean = 0;       // mean two-sided distance: (points -> mesh + mesh -> points) / 2
  double hausdorff = 0;  // largest distance either way
};

struct CompareRow {
  uint32_t level = 0;
  size_t vertices = 0, triangles = 0;  // of the level mesh (the same for dbss, DSS and Draco)
  size_t dbss_samples = 0;             // odd vertices of this level (E of the level before); 0 at level 0
  size_t dss_samples = 0;              // every vertex of this level (V_l); 0 at level 0
  uint64_t dbss_bytes = 0;             // file prefix that decodes levels 0..level
  uint64_t dss_level_bytes = 0;        // header, control mesh and this level's chunk alone
  uint64_t dss_all_bytes = 0;          // header, control mesh and every level's chunk so far
  std::vector<uint64_t> draco_bytes;   // per CompareOptions::draco_bits
  size_t dbss_clamped = 0, dss_clamped = 0;
  RelativeError dbss_error, dss_error;
  std::vector<RelativeError> draco_error;
};

struct Comparison {
  Encoding encoding;
  std::vector<CompareRow> rows;  // levels 0..L
};

// Encodes `points` with `encode` and measures every representation.
Result<Comparison> compare_representations(const PointCloud& points, const EncodeOptions& encode,
                                           const CompareOptions& options = {});

}  // namespace dbss
