// The full-vertex DSS baseline (Lee et al. 2000, reconstructed from points
// as Jeong and Kim do): from the same control mesh, Loop subdivision to each
// level and a displacement sampled for every vertex of that level along its
// normal.  A multiresolution DSS stores every level's full set.  It uses
// dbss's sampler, quantizer and entropy coder, so only the representation
// differs.  A measuring stick for `dbss compare`, not a file format.
#pragma once

#include <cstdint>
#include <vector>

#include "dbss/decoder/mesh.h"
#include "dbss/encoder/point_index.h"
#include "dbss/format/status.h"

namespace dbss {

struct DssOptions {
  uint32_t levels = 3;
  float step = 0;        // quantization step, model units, > 0 (dbss's step)
  int zstd_level = 19;   // as dbss's --effort
  // The sampler's kernels, as dbss's levels chose them for the same points
  // (encode_levels, from point_noise): `widen` on a noisy cloud, `tight`
  // (with the facet hit) on a quiet clean one; sample_displacement.  The
  // defaults are a clean cloud's.
  bool widen = false;
  bool tight = true;
};

struct DssLevel {  // level l of the result is element l - 1
  size_t samples = 0;   // displacements stored for this level: its vertex count V_l
  size_t clamped = 0;   // samples cut to the sampler's limit
  size_t bytes = 0;     // one LEVL-style chunk for the level: framing + zstd payload (smaller coding)
  TriangleMesh mesh;    // Loop^l(control) with the dequantized displacements applied
};

// Levels 1..options.levels.  `control` should be the Draco-decoded control
// mesh dbss continues from.
Result<std::vector<DssLevel>> encode_dss_baseline(const TriangleMesh& control, const PointIndex& points,
                                                  const DssOptions& options);

}  // namespace dbss
